"""What every vendor's package shares and no generic module needs to know
about: the records its readers return. Vendors import it; it imports no vendor."""
