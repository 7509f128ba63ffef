"""Settings of the results run: the full variant and --quick (the test suite's smoke test)."""

# Section 3's events in scenes/cornell_light.gltf (scripts/make_scenes.py LIGHT_TIMELINE): time in
# seconds, id, what happens, and the light's state after it (the reference and converged run are
# made once per state).
DYNAMIC_EVENTS = [
    (4.0, "jump", "the light jumps to B (near the green wall, back)", "B"),
    (14.0, "off", "it is switched off (moved into the housing)", "off"),
    (24.0, "on", "it is switched on again at B", "B"),
]


FULL = {
    "mode": "full",
    "scaling_scenes": ["sponza", "breakfast"],
    "scaling_views": [1, 2, 4, 8, 16, 32, 48],
    # The Looking Glass Portrait tile at the renderer's default MSAA (4 on lavapipe). Measured on
    # the 2-core box under load (4-5), anisotropy off: 1.3-1.8 s a Sponza view, 0.25-0.8 s a
    # Breakfast-room view, so the section (111 views x 3 frames per scene, plus the floor) takes
    # ~9-15 min; MSAA 1 would be ~3x cheaper per view.
    "scaling_tile": (420, 560),
    "scaling_msaa": 4,
    "scaling_frames": 3,
    "raster_floor_frames": 2,
    # Issue 20's output goal: a 10-frame 48-view Sponza run with --every against the same run
    # writing only the last frame (about 1.5 min each on the quiet 2-core box).
    "output_overhead": {"scene": "sponza", "views": 48, "frames": 10},
    # Issue 20's memory goal: single-frame renders of the rig at 1, 8 and 48 views, and the 65"
    # panel's 72 views of 1024x910 against one of its views (about 4 min in all).
    "memory": {"scene": "sponza", "views": (1, 8, 48),
               "large": {"display": "looking-glass-65", "views": 72, "tile": (1024, 910)}},
    "trace_floor": {"samples": 256, "updates": 3, "repeat": 3},
    "error_scenes": {
        "cornell": {"size": (160, 160), "ref_spp": 1024},
        "breakfast": {"size": (160, 120), "ref_spp": 512,
                      # The sidecar's cells are 0.47 x 0.75 x 0.58 m; near-cubic cells for about
                      # the same number of probes (240 against 256) and the paper's 256 paths.
                      "camera_variant": {
                          "label": "grid 6,5,8",
                          "why": "near-cubic cells (0.62 x 0.60 x 0.58 m) for about the sidecar's probe count",
                          "args": ["--grid", "6,5,8", "--probe-samples", 256]}},
        "sponza": {"size": (160, 120), "ref_spp": 512,
                   # Issue 19: the sidecar's z spacing (3.92 m) is one gallery width, so no probe row
                   # lies in the galleries CameraAlcove and CameraBalcony look into. The error here is
                   # bias, not noise (16 paths score within 0.1 dB of 256), so 16x the probes at 1/16
                   # of the paths: 0.76x the paper settings' probe rays (docs/probe-visibility.md).
                   "camera_variant": {
                       "label": "grid 32,16,32 and 16 paths per probe",
                       "why": "16 times the probes, a sixteenth of the paths: no more probe rays than "
                              "the paper settings",
                       "args": ["--grid", "32,16,32", "--probe-samples", 16]}},
    },
    "error_frames": 24,
    # Also the paper settings, equal-time path tracing and direct light from every camera of a
    # scene with several (error_cameras.py).
    "error_all_cameras": True,
    "sweep": {
        "probe_samples": [16, 64, 256],
        # *_fit: --probe-placement fit on that grid (issue 19; docs/probe-visibility.md).
        "grid": ["sidecar", "half", "sidecar_fit", "half_fit"],
        "sh_order": [1, 2, 3, 4],
        "hysteresis": [0.9, 0.95, 0.99],
        "bounces": [4],
    },
    "pt_spp": [1, 2, 4, 8, 16],
    # scenes/cornell_light.gltf, one run per hysteresis and blend from t = 0 to the last event +
    # segment_s. fps per hysteresis: enough frames (one probe update each) between events for the
    # slowest decay, 10 s = 100 frames at 0.9 and 0.95 (theory: 22, 45 frames), 300 at 0.99 (229).
    "dynamic": {
        "size": (96, 96), "ref_spp": 1024, "samples": 64, "hysteresis": [0.9, 0.95, 0.99],
        "blends": ["per-update", "per-sample"], "fps": {0.9: 10.0, 0.95: 10.0, 0.99: 30.0},
        "segment_s": 10.0, "events": DYNAMIC_EVENTS, "still_frames": 300, "still_hysteresis": 0.999,
        # Both blend rules again under a frame budget (visibility schedule), where they differ;
        # 30 fps (300 frames per event): with fewer paths per frame the decay is slower.
        "budget_runs": [{"hysteresis": 0.95, "budget_ms": 30.0, "fps": 30.0}],
    },
    "schedule": {
        "sponza_camera": "CameraAlcove", "size": (160, 120), "ref_spp": 256, "frames": 16,
        "path_frames": 300, "path_size": (96, 96), "path_ref_spp": 1024,
    },
    # Issue 15's soak: 10,000 frames of the animated Cornell box, the budget scheduler on, an
    # image every 100th frame (about 5-6 min at 30 ms a frame).
    "soak": {"frames": 10000, "size": (128, 128), "budget_ms": 30.0, "every": 100},
}

QUICK = {
    "mode": "quick",
    "scaling_scenes": ["cornell"],
    "scaling_views": [1, 4],
    "scaling_tile": (48, 64),
    "scaling_msaa": 1,
    "scaling_frames": 3,
    "raster_floor_frames": 1,
    "output_overhead": {"scene": "cornell", "views": 4, "frames": 3},
    "memory": {"scene": "cornell", "views": (1, 2, 4),
               "large": {"display": "looking-glass-65", "views": 72, "tile": (32, 28)}},
    "trace_floor": {"samples": 16, "updates": 2, "repeat": 1},
    "error_scenes": {"cornell": {"size": (48, 48), "ref_spp": 32}},
    "error_frames": 4,
    "sweep": {
        "probe_samples": [16, 64],
        "grid": ["sidecar", "half", "half_fit"],
        "sh_order": [1, 2],
        "hysteresis": [0.95],
    },
    "pt_spp": [1, 4],
    "dynamic": {
        "size": (32, 32), "ref_spp": 32, "samples": 16, "hysteresis": [0.9],
        "blends": ["per-update", "per-sample"], "fps": {0.9: 1.0}, "segment_s": 10.0,
        "events": DYNAMIC_EVENTS, "still_frames": 30, "still_hysteresis": 0.999,
    },
    "schedule": None,
    "soak": {"frames": 100, "size": (32, 32), "budget_ms": 30.0, "every": 50},
}

# The paper's settings (DDISH-GI): L2 probes, 256 paths per probe per update, the grid of the
# scene's sidecar (../shared/scenes/README.md), hysteresis 0.95 (ddish's default), and ddish's
# default probe path length (15 bounces: the reference's 16 less the rasterized surface).
DEFAULTS = {"probe_samples": 256, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95, "bounces": 15}
DEFAULTS_QUICK = {"probe_samples": 64, "grid": "sidecar", "sh_order": 2, "hysteresis": 0.95, "bounces": 15}
