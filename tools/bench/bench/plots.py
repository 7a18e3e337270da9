"""The PNG plots of RESULTS.md (matplotlib, Debian's python3-matplotlib). Without matplotlib the
report is written without them and says so."""
import os

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # the report says so; scripts/install-deps.sh --bench installs it
    plt = None

MISSING = "python3-matplotlib is not installed (bash scripts/install-deps.sh --bench)"
_META = {"Software": None}  # no version stamp in the file: same figures, same bytes


def available():
    return plt is not None


def table1(results, ref, plot_dir):
    """Regions, storage, back-end time and LocErr_ave over S: dpcr beside the paper."""
    rows = [r for r in (results.get("table1") or {}).get("rows", []) if "error" not in r]
    if plt is None or not rows:
        return None
    paper = ref["paper"]["table1"]["rows"]
    s = [r["S_m"] for r in rows]
    ps = [p["S_m"] for p in paper]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    ax[0][0].plot(s, [r["regions"] for r in rows], "o-", label="dpcr (simulated office)")
    ax[0][0].plot(ps, [p["regions"] for p in paper], "s--", label="paper (quoted)")
    ax[0][0].set_ylabel("regional maps")
    ax[0][1].plot(s, [r["map_storage_bytes"] / 1e6 for r in rows], "o-", label="dpcr: regional maps in RAM")
    ax[0][1].plot(s, [r["map_file_bytes"] / 1e6 for r in rows], "^-", label="dpcr: saved map file")
    ax[0][1].plot(ps, [p["storage_mb"] for p in paper], "s--", label="paper (quoted)")
    ax[0][1].set_ylabel("storage (MB)")
    ax[1][0].plot(s, [r["backend_total_ms"] for r in rows], "o-", label="dpcr: back-end time, this machine")
    ax[1][0].plot(ps, [p["graph_ms"] for p in paper], "s--", label="paper: graph time, its robot (quoted)")
    ax[1][0].set_ylabel("time (ms)")
    minutes = results["table1"]["minutes"]
    ax[1][1].plot(s, [r["loc_err_ave_m"] * 100 for r in rows], "o-", label=f"dpcr {minutes:g} min")
    ax[1][1].plot(ps, [p["loc_err_35min_cm"] for p in paper], "s--", label="paper 35 min (quoted)")
    long_rows = [r for r in (results.get("table1_long") or {}).get("rows", []) if "error" not in r]
    if long_rows:
        ax[1][1].plot([r["S_m"] for r in long_rows], [r["loc_err_ave_m"] * 100 for r in long_rows], "o-",
                      label=f"dpcr {results['table1_long']['minutes']:g} min")
        ax[1][1].plot(ps, [p["loc_err_70min_cm"] for p in paper], "s--", label="paper 70 min (quoted)")
    ax[1][1].set_ylabel("LocErr_ave (cm)")
    for a in (ax[0][0], ax[0][1], ax[1][0], ax[1][1]):
        a.set_xlabel("region width S (m)")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    m = results["machine"]
    fig.suptitle(f"Paper Table 1 vs dpcr, simulated office ({results['command']}, {m['date_utc']})", fontsize=10)
    fig.tight_layout()
    path = os.path.join(plot_dir, "table1_region_width.png")
    fig.savefig(path, dpi=80, metadata=_META)
    plt.close(fig)
    return path


def scan_times(results, plot_dir):
    """Per-scan AddScan time percentiles of every scenario that has them."""
    series = []
    t2 = (results.get("table2") or {}).get("result", {})
    if "scan_times" in t2:
        series.append(("apartment (vacuum)", t2["scan_times"]))
    for r in (results.get("table1") or {}).get("rows", []):
        if r.get("S_m") == 4 and "scan_times" in r:
            series.append(("office S=4 (vacuum)", r["scan_times"]))
    for r in results.get("logs") or []:
        if "scan_times" in r:
            series.append((f"{r['log']} (building)", r["scan_times"]))
    if plt is None or not series:
        return None
    keys = [("p50_ms", "median"), ("p90_ms", "p90"), ("p99_ms", "p99"), ("max_ms", "max")]
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(keys)
    for k, (key, label) in enumerate(keys):
        ax.bar([i + k * width for i in range(len(series))], [s[key] for _, s in series], width, label=label)
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(series))])
    ax.set_xticklabels([name for name, _ in series], fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("Mapper::AddScan (ms, log scale)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    m = results["machine"]
    ax.set_title(f"Per-scan time, {m['cpu_model']} ({results['command']}, {m['date_utc']})", fontsize=9)
    fig.tight_layout()
    path = os.path.join(plot_dir, "scan_times.png")
    fig.savefig(path, dpi=80, metadata=_META)
    plt.close(fig)
    return path
