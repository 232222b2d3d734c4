"""The paper's equations transcribed exactly as printed (transcription) and their verification (verify)."""
