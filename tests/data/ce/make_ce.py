"""Write contact.engineering "Power spectrum" downloads (CSV and TXT) of a known surface.

No real download was available, so these files follow the layout of contact.engineering's
download functions for plotted series (topobank, `topobank/analysis/downloads.py`:
`download_plot_analyses_to_csv` and `download_plot_analyses_to_txt`; series names and units
from topobank-statistics, `workflows/power_spectral_density.py`), with the numbers of an exact
self-affine spectrum in SurfaceTopography's normalisation:

- this tool's 2D PSD C(q) = C0 (q/q0)^(-2(1+H)) on q0 <= q <= q1 (h_rms = 1 um exactly);
- "q/pi x 2D PSD": y = (q/pi) (2 pi)^2 C(q);
- "1D PSD along x": pi * C1D(q), C1D(q) = 4 int_q^q1 k C(k) / sqrt(k^2 - q^2) dk (mpmath);
- "1D PSD along y": 1.1 times the x series (so that choosing it is visible);
- each also "(incl. unreliable data)", continued two more points past q1.

Run: python3 make_ce.py (needs mpmath).
"""

import mpmath as mp

mp.mp.dps = 30
H, Q0, Q1, HRMS = mp.mpf("0.8"), mp.mpf("1e4"), mp.mpf("1e7"), mp.mpf("1e-6")
# h_rms^2 = 2 pi int q C dq = 2 pi C0 q0^2 (1 - (q0/q1)^(2H)) / (2H)
C0 = HRMS**2 * 2 * H / (2 * mp.pi * Q0**2 * (1 - (Q0 / Q1) ** (2 * H)))


def c2d(q):
    return C0 * (q / Q0) ** (-2 * (1 + H)) if Q0 <= q <= Q1 else mp.mpf(0)


def c1d(q):
    # k = q cosh u removes the inverse square root: dk / sqrt(k^2 - q^2) = du.
    if q >= Q1:
        return mp.mpf(0)
    lo = mp.acosh(max(q, Q0) / q) if q < Q0 else mp.mpf(0)
    hi = mp.acosh(Q1 / q)
    return 4 * mp.quad(lambda u: q * mp.cosh(u) * c2d(q * mp.cosh(u)), [lo, hi])


QS = [Q0 * mp.mpf(10) ** (mp.mpf(i) / 10) for i in range(0, 30)]  # 1e4 .. 7.9e6
QU = QS + [Q1 * mp.mpf(10) ** (mp.mpf(i) / 10) for i in (-0, 1)]  # unreliable: past q1
SERIES = []
for tag, qs in (("", QS), (" (incl. unreliable data)", QU)):
    x = [(q, mp.pi * c1d(q)) for q in qs]
    SERIES += [
        ("1D PSD along x" + tag, x),
        ("1D PSD along y" + tag, [(q, 1.1 * c) for q, c in x]),
        ("q/π × 2D PSD" + tag, [(q, q / mp.pi * (2 * mp.pi) ** 2 * c2d(q)) for q in qs]),
    ]
SERIES = [(n, [(q, c) for q, c in s if c > 0]) for n, s in SERIES]
SUBJECT = "synthetic self-affine H = 0.8"
META = {
    "Subject type": "measurement",
    "Subject name": SUBJECT,
    "Creator": "Jane Doe",
    "Instrument name": "Stylus; 2 µm tip",
    "Instrument type": "contact-based",
    "Instrument parameters": "{'tip_radius': {'value': 2.0, 'unit': 'µm'}}",
    "Function name": "Power spectrum",
}


def f(x):
    return repr(float(x))


def csv_field(s):
    return '"' + s.replace('"', '""') + '"' if ";" in s or '"' in s else s


with open("ce-power-spectrum.csv", "w", encoding="utf-8", newline="\n") as out:
    cols = list(META) + ["Data series", "Wavevector (1/m)", "PSD (m³)"]
    out.write(";".join(cols) + "\n")
    for name, rows in SERIES:
        for q, c in rows:
            vals = [META[k] for k in META] + [name, f(q), f(c)]
            out.write(";".join(csv_field(v) for v in vals) + "\n")

with open("ce-power-spectrum.txt", "w", encoding="utf-8", newline="\n") as out:
    out.write("# Power spectrum\n# " + "=" * 14 + "\n")
    head = f"topography: {SUBJECT}"
    lines = [
        head,
        "=" * len(head),
        "Creator: Jane Doe",
        "Instrument name: Stylus; 2 µm tip",
        "Instrument type: contact-based",
        "Instrument parameters: {'tip_radius': {'value': 2.0, 'unit': 'µm'}}",
        "Further arguments of analysis function: {'window': None, 'nb_points_per_decade': 10}",
        "Start time of analysis task: 2025-01-01 00:00:00",
        "End time of analysis task: 2025-01-01 00:00:02",
        "Duration of analysis task: 0:00:02",
        "Version of 'SurfaceTopography': 1.17.0",
        "",
    ]
    out.write("".join("# " + l + "\n" for l in lines))
    for name, rows in SERIES:
        out.write(f"# {name}\n# {'-' * len(name)}\n# Columns: Wavevector (1/m), PSD (m³)\n")
        for q, c in rows:
            out.write(f"{float(q):.18e} {float(c):.18e}\n")
        out.write("\n")
print("C0 =", C0, " h_rms^2 check =", 2 * mp.pi * mp.quad(lambda q: q * c2d(q), [Q0, Q1]))
