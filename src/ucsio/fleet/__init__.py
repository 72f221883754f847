"""Many cells at once: the batch run and its report."""
