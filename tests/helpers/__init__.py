"""Builders and independent methods the tests share (imported as ``helpers.<module>``)."""
