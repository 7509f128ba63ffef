"""Section 5: the probe service (`ddish serve` / `ddish view` on loopback), from one run of
scripts/net_figures.sh: bytes per probe per encoding with the PSNR loss, bytes per second of a
static and an animated scene, probe age at a client, the server's work against 1-8 clients and
the reconnection times of the 4-client x 10-restart fault test, and what a relay forwards."""

import csv
import io

from common import ROOT, log, write_csv

# The blocks net_figures.sh prints, in order: file name, title, what the reader should know.
BLOCKS = [
    ("service_encodings.csv", "Bytes per L2 probe per encoding",
     "The first update of an 8×8×8 grid (every active probe sent), Cornell box; *bytes per probe* "
     "includes the gap-coded index; PSNR of a `view` client's image against the in-process render "
     "of the same probes (∞: identical)."),
    ("service_bandwidth.csv", "Bytes per second, change-driven stream",
     "8×8×8 grid, 64 samples, uniform schedule (every probe traced every tick), 30 ticks/s, "
     "serve's default thresholds (`--delta-threshold` for coefficients, `--moment-threshold` for "
     "the 8×8 moment maps); a static scene against an animated one."),
    ("service_probe_age.csv", "Probe age at a client",
     "Server trace end to the client's upload, in milliseconds, on the client's clock (the server "
     "clock's offset comes from the snapshot replies); 30 ticks/s, `--frame-wait-ms 40`."),
    ("service_clients.csv", "Server work per tick against clients",
     "`busy_ms`: the tick's update + publish + requests answered, without the idle wait; "
     "medians over the ticks with every client connected after the first 30; 64×64 views, "
     "visibility schedule."),
    ("service_reconnect.csv", "Reconnection after a server restart",
     "From the 4-client × 10-restart fault test (`tests/app/serve_restart_cli_test.cpp`): the new "
     "server's bind to each client's snapshot, per client display."),
    ("service_relay.csv", "What a relay forwards",
     "`build/bench/net_relay`: one server publishing compact bricks (4×4×4 probes, every probe "
     "changed every tick) at 30 ticks/s through a `ddish relay` forwarder to probe clients that "
     "decode every frame, all in one process on this machine: a lower bound on the relay's rate "
     "(docs/scaling.md uses it)."),
]


def section_service(runner, cfg, results_dir, report):
    report.append("## 5. Probe service\n")
    if cfg["mode"] != "full":
        report.append("*Not run in the quick variant: `scripts/net_figures.sh` takes a few minutes.*\n")
        return None
    out = runner.run(["bash", str(ROOT / "scripts" / "net_figures.sh"), str(runner.build)],
                     "probe service figures", timeout=1200)
    blocks = [b.strip() for b in out.strip().split("\n\n") if b.strip()]
    if len(blocks) != len(BLOCKS):
        raise RuntimeError(f"net_figures.sh printed {len(blocks)} tables, expected {len(BLOCKS)}")
    report.append("`bash scripts/net_figures.sh` on loopback, the server and its clients on this "
                  "machine at once.\n")
    summary = {}
    for (name, title, note), text in zip(BLOCKS, blocks):
        rows = list(csv.DictReader(io.StringIO(text)))
        header = list(rows[0].keys()) if rows else []
        write_csv(results_dir / name, header, rows)
        report.append(f"**{title}** ([{name}](results/{name})). {note}\n")
        report.append("| " + " | ".join(h.replace("_", " ") for h in header) + " |")
        report.append("|" + " --- |" * len(header))
        for r in rows:
            report.append("| " + " | ".join(r[h] for h in header) + " |")
        report.append("")
        summary[name] = rows
        log(f"service: {name}: {len(rows)} rows")
    return summary
