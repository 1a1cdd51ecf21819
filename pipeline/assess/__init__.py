"""What a result means, pure functions over arrays: the responses derived from the engine's
peaks (declared once), the model's range of validity and its flags, the outcomes of a
comparison (helped, neutral, hurt) with the per-earthquake weights and the quantifiers,
fragility curves fitted from events over intensity levels, and the collapses counted by how
they ended."""
