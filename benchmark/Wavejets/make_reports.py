#!/usr/bin/python3
"""Writes the benchmark reports of benchmark/Wavejets/ (*.md and their *.png) from the CSV files in csv/.

The benchmark programs measure and write CSV only; this script does the report writing:

  /usr/bin/python3 benchmark/Wavejets/make_reports.py [--no-plots] [--only R1,R2] [--csv-dir DIR] [--out-dir DIR]

For each report R, templates/R.md.in holds its prose; `{{table NAME ALIGN [COLUMN=VALUE ...]}}` there is replaced by
csv/NAME.csv as a Markdown table (ALIGN: one letter per column, l or r; only the rows with these values where some
are given, COLUMN^=VALUE for the cells that start with VALUE, '_' standing for a space), `{{summary R}}` by the summary table a function below computes from
the CSV files, `{{list NAME}}` by the one-column csv/NAME.csv as a bulleted list, `{{value NAME KEY}}` by the
value of KEY in the two-column csv/NAME.csv (key,value). The plots (R.png) are drawn from the CSV files with matplotlib
(Debian: python3-matplotlib); without it, the reports are written and the plots kept as they are.
Python standard library otherwise.
"""

import csv
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE_DIR = os.path.join(HERE, "templates")
CSV_DIR = os.path.join(HERE, "csv")  # --csv-dir DIR: read another run's CSV files
OUT_DIR = HERE  # --out-dir DIR: write the reports and plots there
REPORTS = ["results", "accuracy", "accuracy_ponca", "filters", "workflows", "python", "scale_selection"]
MAX_REPORT_BYTES = 40 * 1024


def read_csv(name):
    with open(os.path.join(CSV_DIR, name + ".csv"), newline="") as f:
        return list(csv.reader(f))


def as_float(cell):
    try:
        return float(cell)
    except ValueError:
        return None


def bold_best_relative_H(name, header, row):
    """accuracy_ponca.md: the best of the row in bold, the smallest relative H RMSE among the estimators shown, taken
    from the full-precision grid (csv/accuracy_ponca.h_rmse_grid.csv) so that rounding makes no ties; a trailing '*'
    (some points failed) stays outside the bold."""
    surface = name.split(".h_rmse_", 1)[1]
    noise, k = row[0].split("%, ")
    grid = read_csv("accuracy_ponca.h_rmse_grid")
    full = next(r for r in grid[1:] if r[0] == surface and float(r[1]) == float(noise) and r[2] == k)
    raw = [float(full[grid[0].index(column)]) if cell != "-" else None for column, cell in zip(header[1:], row[1:])]
    best = min(v for v in raw if v is not None)
    return [row[0]] + [f"**{c.rstrip('*')}**" + "*" * (len(c) - len(c.rstrip("*"))) if v == best else c
                       for c, v in zip(row[1:], raw)]


def bold_verdict(name, header, row):
    """A target's verdict in bold where it is written after a colon (accuracy_ponca.md, filters.md); "not met"
    (results.md)."""
    return ["**not met**" if c == "not met" else re.sub(r": (fails|pass|FAIL)$", r": **\1**", c) for c in row]


# Tables whose rendering marks something: name pattern -> function of (table name, header, row).
ROW_STYLES = [(re.compile(r"^accuracy_ponca\.h_rmse_(?!grid)"), bold_best_relative_H),
              (re.compile(r"^(results|accuracy_ponca|scale_selection(_long_ladder)?)\.targets|^filters\.check$"), bold_verdict)]


def markdown_table(name, align, selection=""):
    """csv/NAME.csv as a Markdown table; `selection` ("COLUMN=VALUE ...") keeps the rows that have these values."""
    rows = read_csv(name)
    header, body = rows[0], rows[1:]
    for condition in selection.split():
        column, wanted = condition.replace("_", " ").split("=", 1)
        if column.endswith("^"):  # COLUMN^=VALUE: the cells that start with VALUE
            c = header.index(column[:-1])
            body = [r for r in body if r[c].startswith(wanted)]
        else:
            body = [r for r in body if r[header.index(column)] == wanted]
    if len(align) != len(header):
        sys.exit(f"{name}: {len(header)} columns, alignment '{align}'")
    style = next((f for pattern, f in ROW_STYLES if pattern.search(name)), None)
    if style:
        body = [style(name, header, r) for r in body]
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---:" if a == "r" else "---" for a in align) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in body]
    return "\n".join(lines)


def value(name, key):
    for row in read_csv(name):
        if row and row[0] == key:
            return row[1]
    sys.exit(f"{name}.csv has no key '{key}'")


def summary_results():
    """results.md's summary: the point-set functions against CGAL's jets, from the Speed table."""
    rows = read_csv("results.speed")
    us = {(r[0], r[1]): r for r in rows[1:]}
    lines = ["| function | order, k | us / point, 1 thread | CGAL jet_estimate_normals, same degree and k | "
             "x faster than CGAL | us / point, 2 threads |", "|---|---|---:|---:|---:|---:|"]
    for function, K, k in [("wavejet_estimate_normals", 2, 18), ("wavejet_estimate_normals", 4, 32),
                           ("wavejet_estimate_normals", 6, 96), ("wavejet_estimate_curvatures", 6, 96),
                           ("wavejet_enhance_positions", 6, 96)]:
        seq, par = us[(f"{function}, K {K}, k {k}", "seq")], us[(f"{function}, K {K}, k {k}", "par")]
        cgal = us.get((f"CGAL jet_estimate_normals, degree {K}, k {k}", "seq")) if "normals" in function else None
        lines.append(f"| `{function}` | {K}, {k} | {seq[5]} | {cgal[5] if cgal else '-'} | {seq[6] or '-'} "
                     f"| {par[5]} |")
    return "\n".join(lines)


SUMMARIES = {"results": summary_results}


def write_report(report):
    with open(os.path.join(TEMPLATE_DIR, report + ".md.in")) as f:
        text = f.read()
    text = re.sub(r"\{\{table (\S+) ([lr]+)((?: [^ }=]+=[^ }]+)*)\}\}",
                  lambda m: markdown_table(m.group(1), m.group(2), m.group(3)), text)
    text = re.sub(r"\{\{value (\S+) ([^}]+)\}\}", lambda m: value(m.group(1), m.group(2).strip()), text)
    text = re.sub(r"\{\{list (\S+)\}\}", lambda m: "\n".join("* " + r[0] for r in read_csv(m.group(1))[1:]), text)
    text = re.sub(r"\{\{summary (\S+)\}\}", lambda m: SUMMARIES[m.group(1)](), text)
    if "{{" in text:
        sys.exit(f"{report}: unknown placeholder near '{text[text.index('{{'):][:60]}'")
    path = os.path.join(OUT_DIR, report + ".md")
    with open(path, "w") as f:
        f.write(text.rstrip("\n") + "\n")
    size = os.path.getsize(path)
    if size > MAX_REPORT_BYTES:
        sys.exit(f"{report}.md is {size} bytes, over {MAX_REPORT_BYTES}: keep the grid in its CSV only")
    print(f"wrote {report}.md ({size} bytes)")


# ---------------------------------------------------------------------------------------------------- plots

def columns(rows):
    """Header and a dict column name -> list of floats (None where not a number)."""
    return {h: [as_float(r[i]) for r in rows[1:]] for i, h in enumerate(rows[0])}


def plot_results(plt):
    speed = read_csv("results.speed")
    us = {r[0] + " / " + r[1]: as_float(r[5]) for r in speed[1:]}
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5))
    labels, cgal, ours = [], [], []
    for deg, k in [(2, 18), (4, 32), (6, 96)]:
        labels.append(f"order {deg}, k {k}")
        cgal.append(us[f"CGAL jet_estimate_normals, degree {deg}, k {k} / seq"])
        ours.append(us[f"wavejet_estimate_normals, K {deg}, k {k} / seq"])
    x = range(len(labels))
    left.bar([i - 0.2 for i in x], cgal, 0.4, label="CGAL jet_estimate_normals")
    left.bar([i + 0.2 for i in x], ours, 0.4, label="wavejet_estimate_normals")
    left.set_xticks(list(x), labels)
    left.set_yscale("log")
    left.set_ylabel("us per point (1 thread)")
    left.set_title("Normals: time per point, same order and k")
    left.legend()
    left.grid(axis="y", which="both", alpha=0.3)
    rows = read_csv("results.scaling_n")
    for function, marker in [("wavejet_estimate_normals", "o"), ("wavejet_enhance_positions", "s")]:
        sel = [r for r in rows[1:] if r[0] == function]
        if not sel:
            continue
        right.plot([float(r[3]) for r in sel], [float(r[4]) for r in sel], marker=marker,
                   label=f"{function}, K {sel[0][1]}, k {sel[0][2]}")
    right.set_xscale("log")
    right.set_yscale("log")
    right.set_xlabel("number of points N")
    right.set_ylabel("time (s), 2 threads")
    right.set_title("Time against N")
    if right.lines:
        right.legend()
    right.grid(which="both", alpha=0.3)
    return fig


def plot_accuracy(plt):
    rows = read_csv("accuracy.noise_best")
    surfaces = list(dict.fromkeys(r[0] for r in rows[1:]))
    fig, axes = plt.subplots(2, len(surfaces), figsize=(22, 9))
    fig.suptitle("Wavejets vs CGAL jets: error against position noise "
                 "(best over order K and radius r for each estimator)")
    panels = [("RMSE of H", ["H WJ", "H WJ-R3", "H WJ-T", "H CGAL"]),
              ("mean normal angle (deg)", ["angle WJ", "angle WJ-R3", "angle CGAL", "angle PCA"])]
    for j, surface in enumerate(surfaces):
        sel = [rows[0]] + [r for r in rows[1:] if r[0] == surface]
        data = columns(sel)
        for i, (title, names) in enumerate(panels):
            ax = axes[i][j]
            for name, style in zip(names, ["o-", "s-", "^--", "x:"]):
                ax.plot(data["sigma %"], data[name], style, label=name.split(" ", 1)[1])
            ax.set_yscale("log")
            ax.set_title(f"{surface}: {title}", fontsize=10)
            ax.set_xlabel("noise sigma (% of bbox diagonal)", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8, loc="lower right")
    return fig


def plot_accuracy_ponca(plt):
    rows = read_csv("accuracy_ponca.h_rmse_grid")
    curves = [("CGAL-2", "CGAL jets 2", "s:"), ("WJ-2", "WJ-2", "o-"), ("WJ-4", "WJ-4", "s-"),
              ("WJH-2", "WJH-2 (Hermite)", "^-"), ("WJH-4", "WJH-4 (Hermite)", "v-"),
              ("WJH-2-w10", "WJH-2, weight 10", "D-"), ("APSS", "Ponca APSS", "o--"), ("ASO-s", "Ponca ASO-s", "x-.")]
    noises = ["0", "0.25", "0.5", "1"]
    fig, axes = plt.subplots(2, 4, figsize=(20, 10))
    fig.suptitle("Relative RMSE of H against the number of neighbors k (same neighborhoods for every estimator)")
    for i, surface in enumerate(["torus", "ellipsoid"]):
        for j, noise in enumerate(noises):
            sel = [rows[0]] + [r for r in rows[1:] if r[0] == surface and float(r[1]) == float(noise)]
            data = columns(sel)
            ax = axes[i][j]
            for column, label, style in curves:
                points = [(k, v) for k, v in zip(data["k"], data[column]) if v is not None and v > 0]
                ax.plot([p[0] for p in points], [p[1] for p in points], style, label=label)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xticks([20, 50, 100, 200], ["20", "50", "100", "200"])
            ax.set_title(f"{surface}, noise {noise}%")
            ax.set_xlabel("k")
            ax.grid(which="both", alpha=0.3)
    axes[1][1].legend(fontsize=8, loc="lower left")
    return fig


def plot_filters(plt):
    colors = {2: "#1f77b4", 4: "#d62728", 6: "#2ca02c", 8: "#9467bd"}
    dashes = {"2": "-", "3": "--", "-1": ":", "0": "-."}
    fig, axes = plt.subplots(2, 2, figsize=(14, 10))
    panels = [("filters.positions_grid", "detail", "wavejet_enhance_positions: detail gain", (-3, 5)),
              ("filters.positions_grid", "noise", "wavejet_enhance_positions: noise gain (residual RMS out / in)",
               None),
              ("filters.normals_grid", "detail", "wavejet_enhance_normals: tilt detail gain, relative to gain 1", None),
              ("filters.normals_grid", "noise", "wavejet_enhance_normals: noise gain, relative to gain 1", None)]
    for ax, (name, measure, title, ylim) in zip(axes.flat, panels):
        data = columns(read_csv(name))
        for K, color in colors.items():
            for gain, dash in dashes.items():
                ax.plot(data["lambda/Rf"], data[f"K{K} gain {gain} {measure}"], dash, color=color, marker=".",
                        label=f"K {K}" if gain == "2" else None)
        ax.axhline(1, color="gray", lw=0.8)
        ax.set_xscale("log")
        ax.set_xticks([1, 1.5, 2, 3, 4, 6, 8, 12, 20], ["1", "1.5", "2", "3", "4", "6", "8", "12", "20"])
        ax.set_xlabel("detail wavelength lambda / Rf")
        ax.set_title(title + "\n(gain 2: solid, 3: dashed, -1: dotted, 0: dash-dot)", fontsize=10)
        if ylim:
            ax.set_ylim(*ylim)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=9)
    return fig


def plot_workflows(plt):
    fig, axes = plt.subplots(2, 2, figsize=(15, 9))
    for j, mesh in enumerate(["bunny", "fandisk"]):
        rows = read_csv("workflows." + mesh)
        header = rows[0]
        scans = list(dict.fromkeys(r[0] for r in rows[1:]))
        estimators = list(dict.fromkeys(r[1] for r in rows[1:]))
        width = 0.8 / len(estimators)
        for i, column in enumerate(["mean angle (deg)", "Hausdorff"]):
            ax = axes[i][j]
            c = header.index(column)
            for e, estimator in enumerate(estimators):
                values = [next((as_float(r[c]) for r in rows[1:] if r[0] == s and r[1] == estimator), None)
                          for s in scans]
                ax.bar([x + e * width for x in range(len(scans))], [v or 0 for v in values], width, label=estimator)
            ax.set_xticks([x + 0.4 - width / 2 for x in range(len(scans))], [s.split(" (")[0] for s in scans],
                          fontsize=8)
            ax.set_title(f"{mesh}: {'normal error after orientation' if i == 0 else 'Hausdorff distance'}")
            ax.set_ylabel(column + ("" if i == 0 else " (% of the diagonal)"))
            ax.grid(axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=8)
    return fig


def plot_python(plt):
    """python.md: error against time of every (order, k) of the grid and of Open3D, one panel a surface
    (the noise levels as marker shapes)."""
    rows = read_csv("python.grid")[1:]
    surfaces = list(dict.fromkeys(r[0] for r in rows))
    noises = list(dict.fromkeys(r[1] for r in rows))
    markers = ["o", "s", "^", "D"]
    colors = {"Open3D": "black", "wavejets K 1": "#9467bd", "wavejets K 2": "#1f77b4", "wavejets K 3": "#2ca02c",
              "wavejets K 4": "#d62728"}
    fig, axes = plt.subplots(1, len(surfaces), figsize=(5 * len(surfaces), 4.5))
    for ax, surface in zip(axes, surfaces):
        for method, color in colors.items():
            for noise, marker in zip(noises, markers):
                points = [(float(r[4]), float(r[5])) for r in rows if r[0] == surface and r[1] == noise and r[2] == method]
                if points:
                    ax.plot(*zip(*sorted(points)), marker=marker, color=color, lw=0.8 if method != "Open3D" else 0,
                            ms=7 if method == "Open3D" else 5,
                            label=f"{method} (k {', '.join(r[3] for r in rows if r[2] == method and r[0] == surface and r[1] == noise)})"
                            if noise == noises[-1] else None)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("mean angle error (deg)")
        ax.set_title(f"{surface}: noise {', '.join(f'{n} ({m})' for n, m in zip(noises, markers))}", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=7)
    return fig


PLOTS = {"results": plot_results, "accuracy": plot_accuracy, "accuracy_ponca": plot_accuracy_ponca,
         "filters": plot_filters, "workflows": plot_workflows, "python": plot_python}


def write_plots(reports):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found (Debian: apt-get install python3-matplotlib): plots kept as they are")
        return
    for report in (r for r in reports if r in PLOTS):   # scale_selection has tables only
        fig = PLOTS[report](plt)
        fig.tight_layout()
        fig.savefig(os.path.join(OUT_DIR, report + ".png"), dpi=80)
        plt.close(fig)
        print(f"wrote {report}.png")


def main():
    global CSV_DIR, OUT_DIR
    args = sys.argv[1:]
    reports = REPORTS
    while args:
        option = args.pop(0)
        if option == "--csv-dir" and args:
            CSV_DIR = os.path.abspath(args.pop(0))
        elif option == "--out-dir" and args:
            OUT_DIR = os.path.abspath(args.pop(0))
        elif option == "--only" and args:
            reports = args.pop(0).split(",")
        elif option != "--no-plots":
            sys.exit(__doc__)
    for report in reports:
        write_report(report)
    if "--no-plots" not in sys.argv[1:]:
        write_plots(reports)


if __name__ == "__main__":
    main()
