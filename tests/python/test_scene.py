"""kimp.Scene: the CLI's reader and validation, the same error messages, overrides in SI or
with units."""

import pytest

import kimp
from conftest import run_cli

BAD_SCENE = """\
isolator:
  K1: "200 MN/m"
  K2: "250 MN/m"
walls:
  left:
    gap: "15 cm"
"""


def test_scene_error_has_the_cli_message_file_line_and_key(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(BAD_SCENE)
    cli = run_cli("lumped", path, "-o", tmp_path / "out", check=False)
    assert cli.returncode == 1
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_yaml(str(path))
    message = str(caught.value)
    assert cli.stderr.strip() == f"error: {message}"
    assert caught.value.file == str(path)
    assert caught.value.line == 3
    assert caught.value.key == "isolator.K2"
    assert not (tmp_path / "out").exists()


def test_unknown_key_and_missing_unit_match_the_cli(tmp_path):
    for text in ("walls:\n  gap: 10 cm\n", "walls:\n  left:\n    gap: 10\n"):
        path = tmp_path / "bad.yaml"
        path.write_text(text)
        cli = run_cli("lumped", path, "-o", tmp_path / "out", check=False)
        with pytest.raises(kimp.SceneError) as caught:
            kimp.Scene.from_yaml(path)
        assert cli.stderr.strip() == f"error: {caught.value}"
        assert caught.value.line >= 2


def test_missing_file_is_a_scene_error_like_the_cli(tmp_path):
    path = tmp_path / "missing.yaml"
    cli = run_cli("lumped", path, "-o", tmp_path / "out", check=False)
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_yaml(path)
    assert cli.stderr.strip() == f"error: {caught.value}"


def test_overrides_in_si_and_with_units_resolve_identically():
    scene = kimp.Scene.default()
    with_units = scene.with_(**{"walls.left.gap": "10 cm", "isolator.K1": "300 MN/m",
                                "building.damping_ratio": "3 %", "impact.k": "2000 kN/mm"})
    in_si = scene.with_(walls={"left": {"gap": 0.1}}, isolator={"K1": 300e6},
                        building={"damping_ratio": 0.03}, impact={"k": 2e9})
    a, b = with_units.resolved, in_si.resolved
    # impact.k is a text key (its unit depends on the law's exponent): compare its SI value.
    k_a, k_b = a["impact"].pop("k"), b["impact"].pop("k")
    assert kimp.parse_quantity(k_a, "N/m") == kimp.parse_quantity(k_b, "N/m") == 2e9
    assert a == b
    assert in_si.resolved["walls"]["left"]["gap"] == 0.1
    assert in_si.resolved["isolator"]["K1"] == 300e6
    # An SI number reads back bit for bit.
    odd = scene.with_(**{"walls.right.gap": 0.1234567890123456789})
    assert odd.resolved["walls"]["right"]["gap"] == 0.1234567890123456789


def test_override_errors_name_the_key():
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.default().with_(**{"isolator.K2": "250 MN/m"})
    assert caught.value.key == "isolator.K2"
    assert "< K1 = 200 MN/m" in str(caught.value)


def test_from_dict_to_yaml_round_trip(pounding_scene_file):
    scene = kimp.Scene.from_yaml(pounding_scene_file)
    again = kimp.Scene.from_dict(scene.to_dict())
    assert again.resolved == scene.resolved
    assert kimp.Scene(again.to_yaml()).resolved == scene.resolved
    assert "Scene(kind='lumped'" in repr(scene)


def test_every_kind_has_defaults():
    for kind in kimp._kimp.scene_kinds():
        assert kimp.Scene.default(kind).kind == kind
        assert "#" in kimp.Scene.defaults_text(kind)


def test_paths_of_a_scene_file_are_relative_to_it(tmp_path, monkeypatch):
    site = tmp_path / "site"
    site.mkdir()
    (site / "k_table.csv").write_text(
        "wall_height_m,kelvin_voigt_total_kN_per_mm,jankowski_total_kN_per_mm1.5\n"
        "1,4634.45,2141.86\n2,714.031,208.796\n")
    (site / "scene.yaml").write_text(
        "impact:\n  law: kelvin_voigt\n  k_table: k_table.csv\n  wall_height: 1 m\n")
    (site / "missing.yaml").write_text(
        "impact:\n  law: kelvin_voigt\n  k_table: other.csv\n  wall_height: 1 m\n")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)  # holds no k_table.csv
    kimp.Scene.from_yaml("../site/scene.yaml")
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_yaml("../site/missing.yaml")
    assert caught.value.line == 3
    assert caught.value.key == "impact.k_table"
    assert "../site/other.csv: cannot read the k table" in str(caught.value)


# (scene text, line, column, key) of a message's first failure, as the reader reports them.
LOCATED_ERRORS = [
    ('walls:\n  left:\n    gap: "8 cm"\n  right: [a\n', 5, 1, ""),             # YAML syntax
    ('walls:\n  left:\n    gapp: "8 cm"\n', 3, 0, "walls.left.gapp"),          # unknown key
    ("gapp: 1\n", 1, 0, "gapp"),                                                # ... at the top
    ("walls:\n  left:\n    gap: abc\n", 3, 0, "walls.left.gap"),               # not a quantity
    ("walls:\n  left:\n    gap: 8 cm\n    gap: 9 cm\n", 4, 0, "walls.left.gap"),  # duplicate
    ('walls:\n  left:\n    gap: "-8 cm"\n', 3, 0, "walls.left.gap"),           # out of range
    ("cases:\n  - name: a\n    cor: 2\n", 3, 0, "cases[0].cor"),               # list item
]


@pytest.mark.parametrize("text, line, column, key", LOCATED_ERRORS)
def test_scene_error_attributes_locate_every_kind_of_message(tmp_path, text, line, column, key):
    # A file name with a colon: the location is still told apart from the name.
    path = tmp_path / "site:a.yaml"
    path.write_text(text)
    cli = run_cli("lumped", path, "-o", tmp_path / "out", check=False)
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_yaml(path)
    error = caught.value
    assert cli.stderr.strip().splitlines()[0] == f"error: {error}".splitlines()[0]
    assert (error.file, error.line, error.column, error.key) == (str(path), line, column, key)
    # Without the reader's name the message alone gives the same location.
    alone = kimp.SceneError(str(error))
    assert (alone.line, alone.column, alone.key) == (line, column, key)


def test_missing_file_error_names_the_file_without_a_line(tmp_path):
    path = tmp_path / "missing.yaml"
    with pytest.raises(kimp.SceneError) as caught:
        kimp.Scene.from_yaml(path)
    assert (caught.value.file, caught.value.line, caught.value.key) == (str(path), 0, "")


def test_with_errors_name_the_generated_text_not_the_file(pounding_scene_file):
    scene = kimp.Scene.from_yaml(pounding_scene_file)
    with pytest.raises(kimp.SceneError) as caught:
        scene.with_(**{"isolator.K2": "900 MN/m"})
    error = caught.value
    assert error.file == f"{pounding_scene_file} (with_)"
    assert str(error).startswith(f"{pounding_scene_file} (with_):{error.line}: isolator.K2 = ")
    assert error.key == "isolator.K2"
    # The line is one of the with_ scene's own text (what to_yaml() would give), where K2 is.
    text = kimp.Scene.from_yaml(pounding_scene_file).with_(
        **{"isolator.K2": "20 MN/m"}).to_yaml().splitlines()
    assert '"K2"' in text[error.line - 1]
    # A scene derived twice keeps one suffix, and its paths stay relative to the file.
    twice = scene.with_(**{"walls.left.gap": "9 cm"}).with_(**{"walls.right.gap": "9 cm"})
    assert twice.name == f"{pounding_scene_file} (with_)"
    assert twice.directory == str(pounding_scene_file.parent)


def test_yielding_wall_law_and_study_lists_in_si():
    # The lumped `yielding` wall law's parameters as SI numbers resolve as their unit texts do.
    si = {"envelope": "hyperbolic", "width": 27.78, "height": 1.25, "stiffness": 20.3e6,
          "capacity": 326e3, "failure_ratio": 0.7, "unloading_stiffness": 30e6,
          "tension_capacity": 0.0, "radiation_damping": 395e3, "failure_displacement": 0.1}
    text = {"envelope": "hyperbolic", "width": "27.78 m", "height": "1.25 m",
            "stiffness": "20.3 kN/mm/m", "capacity": "326 kN/m", "failure_ratio": 0.7,
            "unloading_stiffness": "30 kN/mm/m", "tension_capacity": "0 kN/m",
            "radiation_damping": "395 kN*s/m^2", "failure_displacement": "10 cm"}
    a = kimp.Scene.from_dict({"walls": {"left": {"gap": 0.1, "yielding": si}}})
    b = kimp.Scene.from_dict({"walls": {"left": {"gap": "10 cm", "yielding": text}}})
    ya, yb = a.resolved["walls"]["left"]["yielding"], b.resolved["walls"]["left"]["yielding"]
    for key in si:
        assert ya[key] == pytest.approx(yb[key], rel=1e-12), key
    # A list of quantities (the study's wall heights, the pushover's unloading points) in SI.
    study = kimp.Scene.default("study").with_(**{"fem.wall_heights": [1.25, 2.0],
                                                 "fem.pushover.unload_at": [0.01, 0.02]})
    assert study.resolved["fem"]["wall_heights"] == pytest.approx([1.25, 2.0], rel=1e-12)
    assert study.resolved["fem"]["pushover"]["unload_at"] == pytest.approx([0.01, 0.02],
                                                                           rel=1e-12)
