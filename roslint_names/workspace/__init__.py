"""The workspace model: every file's facts joined into one static computation graph."""
