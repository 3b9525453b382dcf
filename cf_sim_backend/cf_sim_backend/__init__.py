"""cf_sim_backend: the embedded 2D soccer simulator and per-player perception/action components."""
