"""The measured UCS: Horn's solver, residuals and exclusion, the determinacy gate,
the reflector offset solved with the frame, and the solution file."""
