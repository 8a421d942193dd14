"""One list and one did-you-mean over every crystal database; --toec messages in the command
line's words; the piezoelectric printout (Euler digits, no negative zero, no stray leaky note).

References: the two databases' own listings (available_materials, available_piezo_materials,
get_cut), read independently of surfwave.real_crystals.catalog; the library call with the same
arguments for printed numbers.
"""
from __future__ import annotations

import json
import re

import pytest

import surfwave
from surfwave.cli import main
from surfwave.errors import InputError
from surfwave.real_crystals.materials import available_materials, get_material
from surfwave.real_crystals.piezo_materials import available_piezo_materials, get_piezo_material


def _run(capsys, *args) -> tuple[int, str, str]:
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_list_names_every_crystal_of_both_databases_with_aliases(capsys):
    """`material --list` holds every canonical name and alias of materials.yaml and of
    piezoelectric.yaml (GaAs twice, once per database); --json gives the same rows."""
    code, out, _ = _run(capsys, "material", "--list")
    assert code == 0
    names = set(available_materials()) | set(available_piezo_materials())
    for n in names:
        assert re.search(rf"^  {re.escape(n)}\s", out, re.M), n
    for alias in ("lithium niobate", "alpha-quartz", "LGS", "copper", "gallium arsenide"):
        assert alias in out, alias
    code, out, _ = _run(capsys, "material", "--list", "--json")
    rows = json.loads(out)
    assert {(r["name"], r["database"]) for r in rows} == (
        {(n, "elastic") for n in available_materials()} | {(n, "piezoelectric") for n in available_piezo_materials()})
    lt = next(r for r in rows if r["name"] == "LiTaO3-Kovacs1990")
    assert lt["aliases"] == list(get_piezo_material("LiTaO3-Kovacs1990").aliases) and lt["symmetry"] == "3m"
    assert next(r for r in rows if r["name"] == "Cu" and r["database"] == "elastic")["toec"] is True


@pytest.mark.parametrize("typed, hint", [
    ("LiNbO", "LiNbO3 (LiNbO3-Warner1967)"),   # a piezoelectric crystal from the elastic lookup
    ("quarz", "quartz (quartz-Bechmann1958)"),
    ("coper", "copper (Cu)"),
    ("LGS2", "LGS (langasite)"),
])
def test_unknown_name_suggests_over_both_databases(capsys, typed, hint):
    """The CLI, the API and both lookups suggest the close name wherever it lives, and list both databases."""
    code, _, err = _run(capsys, "material", "--material", typed)
    assert code == 2 and f"did you mean {hint}" in err
    assert "elastic: Ag" in err and "piezoelectric: AlN" in err
    with pytest.raises(InputError, match=re.escape(hint)):
        surfwave.material(typed)
    for lookup in (get_material, get_piezo_material):
        with pytest.raises(InputError, match=re.escape(hint)):
            lookup(typed)


def test_a_name_of_the_other_database_or_a_cut_is_said_to_be_one():
    with pytest.raises(InputError, match="'LiNbO3' is not in the elastic database: it is LiNbO3-Warner1967 of "
                                         "the piezoelectric database"):
        get_material("LiNbO3")
    with pytest.raises(InputError, match="'copper' is not in the piezoelectric database: it is Cu of the elastic"):
        get_piezo_material("copper")
    with pytest.raises(InputError, match="it names a SAW cut, 128Y-X LiNbO3"):
        surfwave.material("128Y-X")


@pytest.mark.parametrize("args, words", [
    (["--material", "LiNbO3", "--cut", "128Y-X", "--toec"], ["LiNbO3-Warner1967", "--toec-file FILE", "C444"]),
    (["--cut", "ST-X", "--toec", "1", "2", "3", "4", "5", "6"], ["class 32", "--toec-file FILE", "C344"]),
    (["--material", "Fe", "--toec"], ["Fe", "--toec C111 C112 C123 C144 C155 C456", "--toec-file FILE"]),
    (["--C11", "168", "--C12", "121", "--C44", "75", "--rho", "8960", "--toec"], ["--material", "--toec-file"]),
    (["--material", "Cu", "--toec", "1", "2"], ["got 2", "--toec-file FILE"]),
])
def test_toec_errors_name_the_command_line_options(capsys, args, words):
    """Issue 27: the messages said toec=(...) (the Python argument); they say --toec / --toec-file."""
    code, _, err = _run(capsys, "material", *args)
    assert code == 2 and "toec=" not in err and "Traceback" not in err
    for w in words:
        assert w in err, (w, err)


def test_toec_file_errors_name_the_file(tmp_path, capsys):
    f = tmp_path / "set.yaml"
    f.write_text("C111: -1000\n")
    code, _, err = _run(capsys, "material", "--cut", "128Y-X", "--toec-file", str(f))
    assert code == 2 and f"--toec-file {f}:" in err and "C444" in err


def _lines(out: str) -> dict[str, str]:
    return {m.group(1): m.group(2) for m in re.finditer(r"^\s*(\w+) = (.*)$", out, re.M)}


def test_piezo_printout_digits_signs_and_notes(capsys):
    """Euler angles with every digit (ST-X 132.75, not 132.8); no "-0.0000"; the orientation
    printed when no cut is given; the "no leaky root" note only where a leaky wave is expected."""
    code, out, _ = _run(capsys, "material", "--cut", "ST-X")
    assert code == 0 and _lines(out)["euler"].startswith("0 132.75 0 deg")
    code, out, _ = _run(capsys, "material", "--material", "LiNbO3", "--euler", "0", "-0.00001", "0")
    assert code == 0 and not re.search(r"-0\.0+(?![0-9])", out)      # PFA is -1e-16 here
    assert _lines(out)["power_flow_angle"].split()[0] == "0.0000"
    assert _lines(out)["euler"].startswith("0 -0.00001 0 deg")
    code, out, _ = _run(capsys, "material", "--material", "LiNbO3", "--direction", "[010]")
    assert code == 0 and "euler" not in _lines(out)
    assert _lines(out)["surface"] == "(001), direction [010]"
    code, out, _ = _run(capsys, "material", "--cut", "128Y-X")       # subsonic SAW, no leaky root
    r = surfwave.material(cut="128Y-X")
    assert code == 0 and "note" not in out and r["leaky_reason"]      # the library still says why
    assert float(_lines(out)["c_free"].split()[0]) == pytest.approx(float(r["c_free"]), abs=0.006)


def test_negative_zero_is_never_printed():
    from surfwave.cli_piezo import _f

    assert _f(-1e-9, "10.4f") == "    0.0000" and _f(-0.0, "10.2f") == "      0.00"
    assert _f(-0.5, "10.4f") == "   -0.5000" and _f(float("nan"), "10.4f") == "       nan"


def _examples() -> list[tuple[str, str]]:
    """(command, comment) of every ``surfwave material`` example in --help whose comment quotes numbers."""
    from surfwave import cli, cli_piezo

    out = []
    for line in (cli.EPILOG_MATERIAL + cli_piezo.EPILOG).splitlines():
        m = re.match(r"\s*(surfwave material .*?)\s+#\s*(.*\d.*)$", line)
        if m:
            out.append((m.group(1), m.group(2)))
    return out


def test_help_examples_print_the_numbers_they_quote(capsys):
    """Issue 27: --help quoted "128Y-X # 3990 / 3878 m/s, K2 5.6 %" where the command printed
    3994.2 / 3887.6, 5.34 %. Every number of an example's comment must be printed by that
    command, to the comment's decimals."""
    import shlex

    examples = _examples()
    assert len(examples) >= 2
    for command, comment in examples:
        code, out, err = _run(capsys, *shlex.split(command)[1:])
        assert code == 0, (command, err)
        printed = [float(x) for x in re.findall(r"-?\d+\.\d+|-?\d+", out)]
        for quoted in re.findall(r"\d+\.?\d*", comment):
            digits = len(quoted.split(".")[1]) if "." in quoted else 0
            assert any(round(p, digits) == float(quoted) for p in printed), (command, quoted)


def test_readme_cli_examples_print_the_numbers_they_quote(capsys):
    """The README's `surfwave material` lines: every number with decimals in the comment is printed."""
    import shlex
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    lines = re.findall(r"^\.venv/bin/surfwave (material .*?)\s+#\s*(.*\d\.\d.*)$", readme, re.M)
    assert len(lines) >= 3
    for command, comment in lines:
        code, out, err = _run(capsys, *shlex.split(command))
        assert code == 0, (command, err)
        printed = [float(x) for x in re.findall(r"-?\d+\.\d+", out)]
        for quoted in re.findall(r"\d+\.\d+", comment):
            digits = len(quoted.split(".")[1])
            assert any(round(p, digits) == float(quoted) for p in printed), (command, quoted)
