"""Multi-target tracking: the tracker (initiation, track existence, deletion), association (JPDA, PDA, GNN), gating and the per-track filter bank."""
