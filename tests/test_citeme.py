"""The styles register the publications they implement with LAMMPS's citation reminder
(issue 29: a plugin a user can cite): pair thornton/yin the contact law (Thornton & Yin 1991),
fix cell/servo and compute thornton/yin/micromechanics the periodic-cell tests and their
micromechanics (Thornton 2000). LAMMPS prints each registered entry once, as a one-line
notice on the screen and in full BibTeX in the log file."""
import subprocess

from test_pair_input_errors import one_sphere_cell

THORNTON_YIN_1991 = "doi:10.1016/0032-5910(91)80178-L"
THORNTON_2000 = "doi:10.1680/geot.2000.50.1.43"


def run(tmp_path, styles):
    """A sphere alone in a periodic box under pair thornton/yin and `styles`; LAMMPS writes its
    citation notice on the screen and the BibTeX into the log file."""
    (tmp_path / "in.cite").write_text(one_sphere_cell(styles))
    out = subprocess.run(["lmp", "-in", "in.cite", "-log", "log.cite.lammps"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr
    return out.stdout, (tmp_path / "log.cite.lammps").read_text()


def test_pair_alone_cites_the_contact_law_only(tmp_path):
    screen, log = run(tmp_path, "")
    assert screen.count(THORNTON_YIN_1991) == 1
    assert THORNTON_2000 not in screen
    assert log.count("@Article{Thornton1991,") == 1
    assert "Impact of elastic spheres with and without adhesion" in log


def test_cell_and_micromechanics_cite_the_periodic_cell_paper_once(tmp_path):
    screen, log = run(tmp_path, "fix cell all cell/servo iso 1e5 max_rate 1e-3\n"
                                "compute micro all thornton/yin/micromechanics\n")
    assert screen.count(THORNTON_YIN_1991) == 1
    # two styles register the same entry; LAMMPS lists it once
    assert screen.count(THORNTON_2000) == 1
    assert log.count("@Article{Thornton2000,") == 1
    assert "deviatoric shear deformation of granular media" in log
