#!/usr/bin/python3
"""Bsdf.eval from Python on 10^6 direction pairs against bench_bsdf's per-call figure x 10^6, and its thread scaling;
and a 256 x 256 BRDF table from Python against the same table from one `surfscatter brdf eval` process.

The same five models as bench/bench_bsdf.cpp's BM_eval/<model>/2 (KC gamma = 3, L = 1 um, g = 10 at 550 nm,
perfect conductor, theta_i = 30 deg, outgoing directions from the model's own sampler). Each repetition runs
bench_bsdf (one process) and then times one Bsdf.eval call over all pairs per model, first limited to one thread
(surfscatter.set_max_threads(1)), then with every core; then the table: GHS (exact) on a 256 x 256 grid of
theta_o in [0, 89] deg and phi_o in [0, 360) deg, in Python (building the model from its cached tables, and eval
on the grid) and by the CLI (the process's whole run, its CSV written to /dev/null). The figures are medians over the
repetitions, CPU seconds (time.process_time, all threads; the CLI's from os.wait4) and wall seconds
(time.perf_counter) separately. Results go to docs/PERFORMANCE.md.

    /usr/bin/python3 bench/bench_python_bsdf.py --build build
"""

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

MODELS = {  # bench_bsdf.cpp options_for(model, g): name -> keyword options of surfscatter.bsdf
    0: ("ghs_exact", dict(model="ghs")),
    1: ("ghs_refit", dict(model="ghs", method="refit")),
    2: ("ghs_ssa", dict(model="ghs_ssa")),
    3: ("ggx_stats", dict(model="ggx_stats", alpha_from="smoothed", smoothing=0.1)),
    4: ("two_scale", dict(model="two_scale", cutoff_wavelengths=50)),
}
LAMBDA_NM = 550.0
THETA_I_DEG = 30.0
G = 10.0


def load_average():
    return os.getloadavg()


def cpp_per_call(bench):
    """ns per eval call (cpu, real) of BM_eval/<model>/2 from one bench_bsdf run."""
    out = subprocess.run([bench, "--benchmark_filter=BM_eval/[0-4]/2$", "--benchmark_min_time=0.3",
                          "--benchmark_format=json"], capture_output=True, text=True, check=True).stdout
    figures = {}
    for row in json.loads(out)["benchmarks"]:
        model = int(row["name"].split("/")[1])
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6}[row["time_unit"]]
        figures[model] = (row["cpu_time"] * scale, row["real_time"] * scale)
    return figures


def queries(model, ss, pairs):
    """Fixed wi and `pairs` outgoing directions from the model's sampler, as bench_bsdf's directions()."""
    rng = np.random.default_rng(3)
    wi = ss.direction(THETA_I_DEG, 0.0)
    wo, _, pdf, delta = model.sample(wi, LAMBDA_NM, rng.random((pairs, 3)) * [0.999999, 1, 1] + [1e-6, 0, 0])
    redo = (pdf == 0) | delta
    wo[redo] = ss.direction(np.degrees(np.arccos(rng.random(redo.sum()))), rng.uniform(0, 360, redo.sum()))
    return wi, wo


def timed_table_python(ss, options, theta_o, phi_o):
    """CPU and wall seconds of a new model's first table on the theta_o x phi_o grid (its lobe tables are read from
    the disk cache on first use), and of the same table again from the loaded model."""
    def table(model):
        cpu, wall = time.process_time(), time.perf_counter()
        values = model.eval(ss.direction(THETA_I_DEG, 0.0), ss.direction(theta_o[:, None], phi_o[None, :]), LAMBDA_NM)
        assert values.shape == (theta_o.size, phi_o.size)
        return time.process_time() - cpu, time.perf_counter() - wall
    cpu, wall = time.process_time(), time.perf_counter()
    model = ss.bsdf(**options)
    table(model)
    first = (time.process_time() - cpu, time.perf_counter() - wall)
    return first, table(model)


def timed_table_cli(cli, sigma, theta_o, phi_o):
    """CPU (user + system of the process) and wall seconds of the same table by one `surfscatter brdf eval`
    (theta_o and phi_o of one element: a single direction pair)."""
    args = [cli, "brdf", "eval", "--model", "ghs", "--psd", "kc", "--sigma", repr(sigma), "--corr-length", "1",
            "--gamma", "3", "--material", "perfect", "--wavelength", repr(LAMBDA_NM), "--theta-i", repr(THETA_I_DEG),
            "--theta-o", ",".join(repr(float(t)) for t in theta_o), "--phi-o", ",".join(repr(float(p)) for p in phi_o)]
    wall = time.perf_counter()
    with open(os.devnull, "w") as sink:
        process = subprocess.Popen(args, stdout=sink)
        _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - wall
    assert status == 0, f"{' '.join(args[:12])} ... failed"
    return usage.ru_utime + usage.ru_stime, wall


def timed_eval(model, wi, wo):
    cpu, wall = time.process_time(), time.perf_counter()
    model.eval(wi, wo, LAMBDA_NM)
    return time.process_time() - cpu, time.perf_counter() - wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", type=Path, default=Path("build"), help="build directory")
    parser.add_argument("--pairs", type=int, default=10**6)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--table", type=int, default=256, help="n of the n x n BRDF table")
    args = parser.parse_args()
    sys.path.insert(0, str(args.build.resolve() / "python"))
    import surfscatter as ss

    cores = os.cpu_count()
    sigma = np.sqrt(G) / (2 * 2 * np.pi / (LAMBDA_NM * 1e-3))
    models = {m: ss.bsdf(psd="kc", sigma=sigma, corr_length=1.0, gamma=3.0, **options)
              for m, (_, options) in MODELS.items()}
    directions = {m: queries(model, ss, args.pairs) for m, model in models.items()}
    for m, model in models.items():  # tables built before timing
        wi, wo = directions[m]
        model.eval(wi, wo[:16], LAMBDA_NM)

    theta_o = np.linspace(0.0, 89.0, args.table)
    phi_o = np.linspace(0.0, 360.0, args.table, endpoint=False)
    table_options = dict(model="ghs", psd="kc", sigma=sigma, corr_length=1.0, gamma=3.0)
    cli = str(args.build / "apps" / "surfscatter" / "surfscatter")

    load_before = load_average()
    cpp, one, many, table_py, table_eval, table_cli, single_cli = [], [], [], [], [], [], []
    for _ in range(args.repeats):
        cpp.append(cpp_per_call(str(args.build / "bench" / "bench_bsdf")))
        ss.set_max_threads(1)
        one.append({m: timed_eval(model, *directions[m]) for m, model in models.items()})
        ss.set_max_threads(0)
        many.append({m: timed_eval(model, *directions[m]) for m, model in models.items()})
        with_model, eval_only = timed_table_python(ss, table_options, theta_o, phi_o)
        table_py.append({0: with_model})
        table_eval.append({0: eval_only})
        table_cli.append({0: timed_table_cli(cli, sigma, theta_o, phi_o)})
        single_cli.append({0: timed_table_cli(cli, sigma, theta_o[:1], phi_o[:1])})
    load_after = load_average()

    def median(runs, m, i):
        return float(np.median([run[m][i] for run in runs]))

    print(f"machine: {platform.processor() or platform.machine()}, {cores} cores; "
          f"load average before {load_before[0]:.2f}, after {load_after[0]:.2f}")
    print(f"command: /usr/bin/python3 {' '.join(sys.argv)}")
    print(f"{args.pairs} pairs, median of {args.repeats} interleaved repetitions\n")
    print("| model | C++ eval CPU ns/call (wall) | C++ x 10^6: CPU s | Python 1 thread: CPU s, wall s | "
          f"Python / C++ (CPU) | Python {cores} threads: CPU s, wall s | wall speed-up 1 -> {cores} |")
    print("|---|---|---|---|---|---|---|")
    scale = args.pairs / 1e9
    for m, (name, _) in MODELS.items():
        cpp_cpu, cpp_wall = median(cpp, m, 0), median(cpp, m, 1)
        one_cpu, one_wall = median(one, m, 0), median(one, m, 1)
        many_cpu, many_wall = median(many, m, 0), median(many, m, 1)
        print(f"| {name} | {cpp_cpu:.1f} ({cpp_wall:.1f}) | {cpp_cpu * scale:.4f} | {one_cpu:.4f}, {one_wall:.4f} | "
              f"{one_cpu / (cpp_cpu * scale):.2f} | {many_cpu:.4f}, {many_wall:.4f} | {one_wall / many_wall:.2f} |")
    n = args.table
    print(f"\n{n} x {n} GHS BRDF table, {cores} threads:")
    print("| | CPU s | wall s |\n|---|---|---|")
    print(f"| Python: surfscatter.bsdf + first Bsdf.eval (tables read from the disk cache) | "
          f"{median(table_py, 0, 0):.3f} | {median(table_py, 0, 1):.3f} |")
    print(f"| Python: Bsdf.eval again (model loaded) | {median(table_eval, 0, 0):.4f} | {median(table_eval, 0, 1):.4f} |")
    print(f"| CLI: one `surfscatter brdf eval` process for the table | {median(table_cli, 0, 0):.3f} | "
          f"{median(table_cli, 0, 1):.3f} |")
    print(f"| CLI: one `surfscatter brdf eval` process for one direction pair | {median(single_cli, 0, 0):.3f} | "
          f"{median(single_cli, 0, 1):.3f} |")


if __name__ == "__main__":
    main()
