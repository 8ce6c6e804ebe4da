"""The Hess case: the Hess solution, its periods, the pendulums and their Floquet multipliers."""
