"""Bytes to documents with spans to frames: the grammars' runtime, the RAPID and KRL
readers, and controller files, folders and archives as sources."""
