"""Fuzz harness: every extractor and the CLI over hostile and damaged files (see README.md)."""
