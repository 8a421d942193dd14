"""What a reader needs from the figures and tables, without the code.

References: the synthetic cubes built here (which curves coincide, which points are
unstable, which potentials are identical), and the paper's Table I layout (paper_values.yaml).
"""
import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr
from matplotlib.legend_handler import HandlerTuple  # noqa: F401 (the fig2 legend uses it)
from test_report import table1_cubes

from surfwave.data import cube
from surfwave.plots import dispersion as pdisp
from surfwave.plots import speeds
from surfwave.plots.labels import potential_label
from surfwave.report import benchmarks, reproduction


def _fcc(tmp_path, coincide: bool, unstable: bool):
    d = np.linspace(0.95, 1.05, 11)
    x = d - 1
    dims = ("potential", "direction", "strain")
    base = {"stress": x, "c2_L_par": 1 + x, "c2_T_par": 0.5 + x, "c2_L_perp": 1 - x,
            "c2_T_perp": 0.5 - x, "c2_SH": (0.5 + x) if coincide else 0.2 + x}
    el = xr.Dataset({k: (dims, np.broadcast_to(v, (1, 2, d.size)).copy(), {"units": "1"}) for k, v in base.items()},
                    coords={"potential": ["morse"], "direction": ["[100]", "[110]"], **cube.strain_coords(d)})
    stable = np.ones((1, 2, d.size), bool)
    if unstable:
        stable[..., :2] = False
    el["stable"] = (dims, stable)
    ra = xr.Dataset({"c2_R": (dims, np.broadcast_to(0.3 + x, (1, 2, d.size)).copy()),
                     "wave_type": (dims, np.full((1, 2, d.size), "surface"))}, coords=el.coords)
    return el, ra


def _legend_texts(fig_path, monkeypatch, el, ra):
    seen = {}

    def keep(fig, path, dpi=150):  # inspect the figure; skip the slow PNG rendering
        seen["labels"] = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
        seen["titles"] = [ax.get_title() for ax in fig.axes]
        plt.close(fig)
        return path

    monkeypatch.setattr(speeds, "savefig", keep)
    speeds.fig2(el, ra, fig_path)
    return seen


def test_fig2_legend_lists_what_is_drawn(tmp_path, monkeypatch):
    """No instability anywhere: no instability entries; coinciding c_SH^2 = c_T,par^2 named;
    the potential by its name (Morse), not its registry key."""
    el, ra = _fcc(tmp_path, coincide=True, unstable=False)
    seen = _legend_texts(tmp_path / "f.png", monkeypatch, el, ra)
    labels = " ".join(seen["labels"])
    assert "unstable" not in labels and "shear instability" not in labels and "supersonic" not in labels
    assert "curves coincide" in labels
    assert "Morse" in seen["titles"][0] and "morse" not in seen["titles"][0]


def test_fig2_legend_shows_instability_when_drawn(tmp_path, monkeypatch):
    el, ra = _fcc(tmp_path, coincide=False, unstable=True)
    seen = _legend_texts(tmp_path / "f.png", monkeypatch, el, ra)
    labels = " ".join(seen["labels"])
    assert "bulk lattice unstable" in labels and "curves coincide" not in labels


def _displacements(identical: bool):
    theta = np.array([0.05, 0.5]) * np.pi
    rows = 4
    u = (0.3 + 0.1j) * np.exp(-np.arange(rows))[None, None, :] * np.ones((1, theta.size, 1))
    v = (0.9j) * np.exp(-np.arange(rows))[None, None, :] * np.ones((1, theta.size, 1))
    other = 1.0 if identical else 0.5
    ds = xr.Dataset({"u": (("potential", "strain", "theta", "row"), np.stack([u, other * u])),
                     "v": (("potential", "strain", "theta", "row"), np.stack([v, v]))},
                    coords={"potential": ["harmonic", "lj"], "theta": theta, "row": np.arange(rows),
                            **cube.strain_coords([1.0])})
    return ds


@pytest.mark.parametrize("identical", [True, False])
def test_fig3_axes_scale_legend_and_identical_note(tmp_path, monkeypatch, identical):
    """Rows labelled, x in d0, a legend for crosses, ellipses and dots, a scale bar, one panel
    per theta, and the note when another potential gives the identical pattern."""
    seen = {}

    def keep(fig, path):  # inspect the figure; skip the slow PNG rendering
        seen["fig"] = fig
        seen["axes"] = [(ax.get_ylabel(), ax.get_xlabel(), [t.get_text() for t in ax.get_yticklabels()],
                         [t.get_text() for t in ax.texts], ax.get_title()) for ax in fig.axes]
        seen["legend"] = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
        seen["title"] = fig._suptitle.get_text()
        plt.close(fig)
        return path

    monkeypatch.setattr(pdisp, "_save", keep)
    pdisp.plot_displacements(_displacements(identical), tmp_path / "f.png", potential="lj")
    first = seen["axes"][0]
    assert len(seen["axes"]) == 2 and "row" in first[0] and "d_0" in first[1]
    assert first[2][0] == "0 (surface)" and any("amplitude 1" in t for t in first[3])
    assert any("equilibrium" in t for t in seen["legend"]) and any("t = 0" in t for t in seen["legend"])
    assert any("trajectory" in t for t in seen["legend"])
    assert "Lennard-Jones" in seen["title"]
    assert ("identical for harmonic" in seen["title"]) == identical


def test_potential_labels():
    """Names a reader knows; other registered potentials from the registry description."""
    assert potential_label("lj") == "Lennard-Jones 12-6"
    assert potential_label("morse").startswith("Morse")


def test_table1_md_readable_and_flags_unstable(tmp_path):
    """One title, at most ~100 characters a line in the tables, unstable rows flagged."""
    e, r = table1_cubes(tmp_path)
    ds = xr.open_dataset(e, engine="h5netcdf").load()
    ds["stable"][..., :4] = False  # d/d0 = 0.88 .. 0.91, as our full check finds
    ds.to_netcdf(tmp_path / "el2.nc", engine="h5netcdf")
    reproduction.table1(tmp_path / "el2.nc", r, tmp_path / "t.md", tmp_path / "t.csv")
    md = (tmp_path / "t.md").read_text()
    assert md.count("Table I") == 1
    table_lines = [ln for ln in md.splitlines() if ln.startswith("|")]
    assert max(map(len, table_lines)) <= 110
    assert "d/d0 = 0.88, 0.89, 0.90, 0.91" in md
    row = next(ln for ln in table_lines if ln.startswith("| 0.88 |"))
    assert "NO" in row
    assert "yes" in next(ln for ln in table_lines if ln.startswith("| 0.92 |"))


def test_benchmark_table_rows_in_words(tmp_path):
    """One row per method and knob with the default, its error, its time and why; a cube of
    the generic convention gets its row; a missing directory says 'not computed'."""
    batch = [1000, 10000, 100000]
    ray = xr.Dataset({"time": ("batch", [1.0, 0.5, 0.5]), "points_per_second": ("batch", [1e6, 2e6, 2.05e6]),
                      "error": ("batch", [3e-15] * 3, {"units": "K d0^2/m"})},
                     coords={"batch": batch}, attrs={"default": 10000})
    (tmp_path / "rayleigh").mkdir()
    ray.to_netcdf(tmp_path / "rayleigh" / "rayleigh_throughput.nc")
    (tmp_path / "a").mkdir()
    xr.Dataset({"error": ("n", [1e-2, 1e-4], {"units": "1"}), "time": ("n", [0.1, 1.0])}, coords={"n": [8, 32]},
               attrs={"method": "slab", "knob": "n", "default": 32, "default_reason": "meets 1e-4"}
               ).to_netcdf(tmp_path / "a" / "slab.nc")
    text = benchmarks.benchmark_table([tmp_path / "rayleigh", tmp_path / "a", tmp_path / "c"], tmp_path / "t.md")
    lines = text.splitlines()
    assert lines[0] == "| " + " | ".join(benchmarks.HEAD) + " |"
    assert lines[2].startswith("| Rayleigh speed, Eq. (17)") and "10,000 points" in lines[2]
    assert "2 million points/s" in lines[2] and "3e-15 K d0^2/m" in lines[2] and "10 %" in lines[2]
    assert lines[3] == "| slab | n | 32 | 0.0001 1 | 1 s | meets 1e-4 |"
    assert lines[4] == "| c | | | | | not computed |"
    assert "_error" not in text and "theta_error_exact" not in text


def test_fig2_single_panel_legend_fits_the_image(tmp_path, monkeypatch):
    """One potential (table1's LJ): the legend of every drawn curve lies inside the image (it was
    five columns wide on a one-panel figure, cut off on both sides)."""
    el, ra = _fcc(tmp_path, coincide=True, unstable=True)
    seen = {}

    def keep(fig, path, dpi=150):
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        w, h = fig.canvas.get_width_height()
        seen["boxes"] = [leg.get_window_extent(r) for leg in fig.legends]
        seen["size"] = (w, h)
        plt.close(fig)
        return path

    monkeypatch.setattr(speeds, "savefig", keep)
    speeds.fig2(el, ra, tmp_path / "f.png", title="one panel")
    (box,) = seen["boxes"]
    w, h = seen["size"]
    assert box.x0 >= 0 and box.x1 <= w and box.y0 >= 0 and box.y1 <= h, (box, seen["size"])


def _acoustoelastic(coincide: bool):
    s = np.linspace(-0.5, 0.5, 5)
    along = 2000 * (1 + 0.01 * s)
    fixed = np.stack([along, 0 * s + 2000, along if coincide else 2000 * (1 + 0.02 * s)])   # along, across, biaxial
    toec = np.stack([fixed, fixed * (1 + 0.001 * s)])                                      # toec False, True
    c = toec.transpose(1, 0, 2)[None, None, None]                # (material, surface, angle, loading, toec, stress)
    dims = ("material", "surface", "angle", "loading", "toec", "stress")
    return xr.Dataset({"c_R": (dims, c), "wave_type": (dims, np.full(c.shape, "surface"))},
                      coords={"material": ["Cu"], "surface": ["(001)"], "angle": [0.0],
                              "loading": ["along", "across", "biaxial"], "toec": [False, True], "stress": s})


@pytest.mark.parametrize("coincide", [True, False])
def test_acoustoelastic_legend_says_when_along_and_biaxial_coincide(tmp_path, monkeypatch, coincide):
    """Fixed constants: a stress across the propagation does not enter, so "along" and
    "biaxial" are one curve; the legend says so (only when they do coincide in the cube)."""
    from surfwave.plots import surface_wave

    seen = {}

    def keep(fig, path, dpi=150):
        seen["labels"] = " ".join(t.get_text() for leg in fig.legends for t in leg.get_texts())
        plt.close(fig)
        return path

    monkeypatch.setattr(surface_wave, "savefig", keep)
    surface_wave.speeds_vs_stress(_acoustoelastic(coincide), tmp_path / "a.png")
    assert ("along = biaxial" in seen["labels"]) == coincide
