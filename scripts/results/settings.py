"""Settings of the results run: the full variant and --quick (the test suite's smoke test)."""


FULL = {
    "mode": "full",
    "scaling_scenes": ["sponza", "breakfast"],
    "scaling_views": [1, 2, 4, 8, 16, 32, 48],
    "scaling_tile": (210, 280),
    "scaling_msaa": 1,
    "scaling_frames": 3,
    "raster_floor_frames": 2,
    "trace_floor": {"samples": 256, "updates": 3, "repeat": 3},
    "error_scenes": {
        "cornell": {"size": (160, 160), "ref_spp": 1024},
        "breakfast": {"size": (160, 120), "ref_spp": 512},
        "sponza": {"size": (160, 120), "ref_spp": 512},
    },
    "error_frames": 24,
    "sweep": {
        "probe_samples": [16, 64, 256],
        "grid": ["sidecar", "half"],
        "sh_order": [1, 2, 3, 4],
        "hysteresis": [0.9, 0.95, 0.99],
    },
    "pt_spp": [1, 2, 4, 8, 16],
    "dynamic": {
        "size": (96, 96), "ref_spp": 1024, "samples": 64, "hysteresis": [0.9, 0.95, 0.99],
        "start_time": 2.0, "fps": 30.0, "moving_frames": 60, "static_frames": 180,
        "motion_times": [2.5, 3.0, 3.5],
    },
    "schedule": {
        "sponza_camera": "CameraAlcove", "size": (160, 120), "ref_spp": 256, "frames": 16,
        "path_frames": 300, "path_size": (96, 96), "path_ref_spp": 1024,
    },
}

QUICK = {
    "mode": "quick",
    "scaling_scenes": ["cornell"],
    "scaling_views": [1, 4],
    "scaling_tile": (48, 64),
    "scaling_msaa": 1,
    "scaling_frames": 3,
    "raster_floor_frames": 1,
    "trace_floor": {"samples": 16, "updates": 2, "repeat": 1},
    "error_scenes": {"cornell": {"size": (48, 48), "ref_spp": 32}},
    "error_frames": 4,
    "sweep": {
        "probe_samples": [16, 64],
        "grid": ["sidecar", "half"],
        "sh_order": [1, 2],
        "hysteresis": [0.95],
    },
    "pt_spp": [1, 4],
    "dynamic": {
        "size": (32, 32), "ref_spp": 32, "samples": 16, "hysteresis": [0.9],
        "start_time": 3.8, "fps": 30.0, "moving_frames": 6, "static_frames": 12,
        "motion_times": [],
    },
    "schedule": None,
}

# The paper's settings (DDISH-GI): L2 probes, 256 paths per probe per update, the grid of the
# scene's sidecar (../shared/scenes/README.md), hysteresis 0.95 (ddish's default).
DEFAULTS = {"probe_samples": 256, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95}
DEFAULTS_QUICK = {"probe_samples": 64, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95}
