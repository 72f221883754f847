"""What a reviewer reads and what gets written: frame deltas, file and backup
comparisons, and patches that change only a frame's numbers."""
