"""Frame algebra in one place: poses, the vendors' rotation conventions (plain math)."""
