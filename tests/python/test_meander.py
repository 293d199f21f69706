"""The Python package: the same invariants as the C++ tests, through numpy arrays, and the
same results as the command line for the same parameters."""

import json
import pathlib
import subprocess
import sys
import warnings

import numpy as np
import pytest

import meander
from conftest import check_certificate, check_closed_manifold, components

SQUARE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)


@pytest.fixture(scope="module")
def sphere():
    return meander.generate("sphere", 2000)


# Meshes from arrays ---------------------------------------------------------------------


@pytest.mark.parametrize("dtype", [np.float32, np.float64, np.int64])
@pytest.mark.parametrize("order", ["C", "F"])
def test_vertices_of_any_number_type_and_layout_are_read(dtype, order):
    vertices = np.asarray(SQUARE, dtype=dtype, order=order)
    mesh = meander.Mesh(vertices, np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32))
    assert mesh.vertices.dtype == np.float32
    np.testing.assert_array_equal(mesh.vertices, SQUARE)
    np.testing.assert_array_equal(mesh.faces, [[0, 1, 2], [0, 2, 3]])


def test_a_strided_view_is_read_as_its_elements():
    wide = np.zeros((4, 6), dtype=np.float64)
    wide[:, ::2] = SQUARE
    mesh = meander.Mesh(wide[:, ::2], [[0, 1, 2, 3]])
    np.testing.assert_array_equal(mesh.vertices, SQUARE)


def test_polygons_of_several_sizes_come_as_lists_or_offsets():
    vertices = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 2, 0], [0, 1, 0], [1, -1, 0]], dtype=np.float32)
    listed = meander.Mesh(vertices, [[0, 1, 2, 3, 4], [0, 5, 1]])
    flat = meander.Mesh(vertices, np.array([0, 1, 2, 3, 4, 0, 5, 1]), offsets=np.array([0, 5, 8]))
    for mesh in (listed, flat):
        np.testing.assert_array_equal(mesh.offsets, [0, 5, 8])
        np.testing.assert_array_equal(mesh.indices, [0, 1, 2, 3, 4, 0, 5, 1])
        with pytest.raises(ValueError, match="not all of one size"):
            mesh.faces


def test_a_meshs_vertices_are_read_only():
    mesh = meander.Mesh(SQUARE, [[0, 1, 2, 3]])
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 5


@pytest.mark.parametrize(
    "vertices, faces, offsets, error, message",
    [
        (SQUARE[:, :2], [[0, 1, 2]], None, ValueError, r"vertices: expected an \(N, 3\) array"),
        (np.array([["a", "b", "c"]]), [[0, 0, 0]], None, TypeError, "vertices: expected numbers"),
        (SQUARE, [[0, 1, 9]], None, ValueError, "face 0 uses vertex 9, but the mesh has 4 vertices"),
        (SQUARE, [[0, 1, 2], [0, 1]], None, ValueError, "face 1 has 2 corners"),
        (SQUARE, np.array([[0.0, 1.0, 2.0]]), None, TypeError, "faces: expected integers"),
        (SQUARE, [[0, -1, 2]], None, ValueError, "entry 1 is -1"),
        (SQUARE, np.array([0, 1, 2, 3]), np.array([0, 3]), ValueError, "offsets: expected F \\+ 1 entries"),
        (SQUARE, "faces", None, ValueError, "faces: expected an \\(F, k\\) array"),
    ],
)
def test_bad_arrays_are_refused_naming_what_is_wrong(vertices, faces, offsets, error, message):
    with pytest.raises(error, match=message):
        meander.Mesh(vertices, faces, offsets=offsets)


# Curves ---------------------------------------------------------------------------------


# The Möbius band's note (not orientable) is a warning.
@pytest.mark.filterwarnings("ignore::meander.MeshWarning")
@pytest.mark.parametrize("shape", ["sphere", "torus", "pretzel", "grid", "moebius"])
def test_one_closed_curve_per_component_with_its_certificate(shape):
    mesh = meander.generate(shape, 1500)
    curves, triangles, cycle_start = meander.curve(mesh, certificate=True, samples=3)
    check_certificate(mesh, curves, triangles, cycle_start, samples=3)


def test_several_components_get_a_curve_each(sphere):
    vertices = np.concatenate([sphere.vertices, sphere.vertices + np.float32(3)])
    faces = np.concatenate([sphere.faces, sphere.faces + sphere.num_vertices])
    two = meander.Mesh(vertices, faces)
    curves, triangles, cycle_start = meander.curve(two, certificate=True, tree="bfs")
    assert len(curves) == 2
    check_certificate(two, curves, triangles, cycle_start)


def test_the_same_seed_gives_the_same_curve_and_another_seed_another(sphere):
    first = meander.curve(sphere, seed=5)
    again = meander.curve(sphere, seed=5)
    other = meander.curve(sphere, seed=6)
    np.testing.assert_array_equal(first[0], again[0])
    assert not np.array_equal(first[0], other[0])


# The Möbius band's note (not orientable) is a warning.
@pytest.mark.filterwarnings("ignore::meander.MeshWarning")
def test_real_meshes_get_one_curve_per_component_with_a_valid_certificate(shared):
    for name in ["spot_control_mesh.obj", "genus3hexa1.obj", "platonic_shelf.obj", "eight.off", "fandisk_quads.off",
                 "camelhead.off", "moebius.obj", "bob_small.ply"]:
        mesh = meander.read(shared / name)
        assert mesh.name == str(shared / name)
        curves, triangles, cycle_start = meander.curve(mesh, certificate=True)
        check_certificate(mesh, curves, triangles, cycle_start)


def test_a_curve_at_a_spacing_is_the_command_lines(shared, cli, tmp_path):
    source = shared / "fertility.off"
    out = tmp_path / "curve.ply"
    subprocess.run([cli, "curve", str(source), "-o", str(out), "--spacing", "4", "--seed", "3", "--tree", "bfs"],
                   check=True, capture_output=True)
    expected = meander.read_curves(out)
    got = meander.curve(meander.read(source), spacing=4, seed=3, tree="bfs")
    assert len(got) == len(expected) == components(meander.read(source))
    for a, b in zip(got, expected):
        np.testing.assert_array_equal(a, b)


def test_model_size_scales_and_lengths_take_units(sphere):
    curves = meander.curve(sphere, model_size="100mm", spacing="8mm", relax=2)
    points = np.concatenate(curves)
    extent = points.max(axis=0) - points.min(axis=0)
    assert extent.max() == pytest.approx(100, rel=0.02)
    inches = meander.curve(sphere, model_size="3.937in", spacing=8, relax=2)
    assert (np.concatenate(inches).max(axis=0) - np.concatenate(inches).min(axis=0)).max() == pytest.approx(100, rel=0.02)


# Wires and duotones ---------------------------------------------------------------------


@pytest.mark.parametrize("method", ["constant", "variable"])
def test_a_wire_is_a_closed_manifold_with_its_report(sphere, method):
    vertices, faces, report = meander.wire(sphere, method=method)
    assert vertices.dtype == np.float32 and vertices.shape[1] == 3
    assert faces.dtype == np.int32 and faces.max() < len(vertices)
    check_closed_manifold(faces)
    assert report["watertight"] is True
    assert report["self_intersecting"] is False
    assert report["printable"] is True
    assert report["radius"] > 0 if method == "constant" else True


def test_a_wire_is_the_command_lines(shared, cli, tmp_path):
    source = shared / "eight.off"
    out, report_path = tmp_path / "wire.ply", tmp_path / "report.json"
    subprocess.run([cli, "wire", str(source), "-o", str(out), "--report", str(report_path), "--model-size", "80mm",
                    "--sides", "6", "--seed", "9"], check=True, capture_output=True)
    vertices, faces, report = meander.wire(meander.read(source), model_size="80mm", sides=6, seed=9)
    written = meander.read(out)
    np.testing.assert_array_equal(vertices, written.vertices)
    np.testing.assert_array_equal(faces, written.faces)
    expected = json.loads(report_path.read_text())
    report.pop("radius")
    assert report == expected


@pytest.mark.parametrize("method", ["constant", "variable"])
def test_a_bridged_wire_is_the_command_lines_one_piece(shared, cli, tmp_path, method):
    source = shared / "eight.off"
    out, report_path = tmp_path / "bridged.ply", tmp_path / "report.json"
    subprocess.run([cli, "wire", str(source), "-o", str(out), "--report", str(report_path), "--model-size", "80mm",
                    "--spacing", "4mm", "--bridges", "16mm", "--method", method, "--levels", "1"],
                   check=True, capture_output=True)
    vertices, faces, report = meander.wire(meander.read(source), model_size="80mm", spacing="4mm", bridges="16mm",
                                           method=method, levels=1)
    written = meander.read(out)
    np.testing.assert_array_equal(vertices, written.vertices)
    np.testing.assert_array_equal(faces, written.faces)
    report.pop("radius")
    assert report == json.loads(report_path.read_text())
    assert report["bridges"]["count"] > 0 and report["bridges"]["one_piece"] is True
    assert len(report["components"]) == 1 and report["components"][0]["euler_characteristic"] < 0
    assert report["self_intersecting"] is False and report["watertight"] is True


def test_a_two_colour_print_is_the_command_lines(shared, cli, tmp_path):
    source = shared / "eight.off"
    args = dict(model_size="100mm", spacing="3mm", shell="1.5mm", colors="red,navy")
    subprocess.run([cli, "duotone", str(source), "-o", str(tmp_path / "cli.3mf"), "--parts",
                    f"{tmp_path / 'a.ply'},{tmp_path / 'b.ply'}"] + [x for k, v in args.items()
                                                                     for x in ("--" + k.replace("_", "-"), v)],
                   check=True, capture_output=True)
    (first, second), summary = meander.duotone_print(meander.read(source), **args)
    assert summary.startswith("2 solids, one per colour, closed and outward")
    for solid, name in [(first, "a.ply"), (second, "b.ply")]:
        written = meander.read(tmp_path / name)
        np.testing.assert_array_equal(solid.vertices, written.vertices)
        np.testing.assert_array_equal(solid.faces, written.faces)
    meander.write_print(tmp_path / "python.3mf", first, second, colors=["red", "navy"])
    assert (tmp_path / "python.3mf").read_bytes() == (tmp_path / "cli.3mf").read_bytes()
    with pytest.raises(ValueError, match="duotone_print"):
        meander.duotone(meander.read(source), shell=1)
    with pytest.raises(ValueError, match="shell"):
        meander.duotone_print(meander.read(source))
    # With a clearance, two pieces to print apart: the summary says how far apart.
    (first, second), summary = meander.duotone_print(meander.read(source), clearance="0.2mm", **args)
    assert "apart" in summary and "clearance 0.2" in summary
    with pytest.raises(ValueError, match="clearance"):
        meander.duotone(meander.read(source), clearance=0.2)


def test_a_duotone_has_its_texture_and_coordinates_and_its_curve(sphere, tmp_path):
    vertices, faces, uv, texture, curves = meander.duotone(sphere, texture_size=256, colors=["#ff0000", "#102030"], subdivide=1)
    assert faces.shape[1] == 4 and faces.max() < len(vertices)
    assert uv.shape == (faces.size, 2) and uv.dtype == np.float32
    assert ((uv >= 0) & (uv <= 1)).all()
    assert texture.dtype == np.uint8 and texture.shape[1] == 256 and texture.shape[2] == 4
    colours = {tuple(c) for c in np.unique(texture[..., :3].reshape(-1, 3), axis=0).tolist()}
    assert (255, 0, 0) in colours and (0x10, 0x20, 0x30) in colours
    assert len(curves) == 1
    for name in ["duotone.glb", "duotone.obj"]:
        meander.write_duotone(tmp_path / name, vertices, faces, uv, texture)
        assert (tmp_path / name).stat().st_size > 0
    assert (tmp_path / "duotone.mtl").exists()


# Pictures and files ---------------------------------------------------------------------


def test_render_draws_the_curve_over_its_surface(sphere, tmp_path):
    curves = meander.curve(sphere)
    picture = meander.render(curves=curves, occluder=sphere, size="160x120", samples=1)
    assert picture.shape == (120, 160, 4) and picture.dtype == np.uint8
    red = (picture[..., 0] > 150) & (picture[..., 1] < 100)
    assert red.sum() > 500, "the curve is not drawn"
    meander.write_png(tmp_path / "curve.png", picture)
    assert (tmp_path / "curve.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # One mesh and one curve need no list; the shaded sphere covers a good part of the picture.
    shaded = meander.render(meshes=sphere, curves=curves[0], size="80x60", samples=1)
    drawn = (shaded[..., :3] < 240).any(axis=2)
    assert drawn.sum() > 0.2 * 80 * 60


@pytest.mark.parametrize("extension", ["obj", "ply", "stl", "off", "glb", "3mf"])
def test_meshes_written_read_back(sphere, tmp_path, extension):
    path = tmp_path / f"sphere.{extension}"
    meander.write_mesh(path, sphere)
    if extension == "3mf":
        assert path.stat().st_size > 0  # 3MF is written only
        return
    back = meander.read(path)
    assert back.num_faces == sphere.num_faces
    np.testing.assert_allclose(np.sort(back.vertices, axis=0), np.sort(sphere.vertices, axis=0), atol=1e-5)


@pytest.mark.parametrize("extension", ["obj", "ply"])
def test_curves_written_read_back(sphere, tmp_path, extension):
    curves = meander.curve(sphere)
    meander.write_curves(tmp_path / f"c.{extension}", curves)
    back = meander.read_curves(tmp_path / f"c.{extension}")
    np.testing.assert_allclose(back[0], curves[0], atol=1e-5)


def test_curves_are_written_as_json_and_svg_too(sphere, tmp_path):
    curves = meander.curve(sphere)
    meander.write_curves(tmp_path / "c.json", curves)
    assert json.loads((tmp_path / "c.json").read_text())
    meander.write_curves(tmp_path / "c.svg", curves, millimetres=True)
    assert b"<svg" in (tmp_path / "c.svg").read_bytes()[:400]


# Refusals -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "parameters, message",
    [
        ({"samples": 0}, r"^samples: expected an integer in \[1, 1000\], got 0$"),
        ({"tree": "nope"}, r"^tree: unknown value 'nope' \(expected random, uniform, bfs, dfs or shaped\)$"),
        ({"spacing": -1}, "spacing: expected a positive number or none"),
        ({"spacing": "3mm"}, "spacing: 3mm carries a unit, which needs model_size"),
        ({"branches": 2}, r"branches: expected a number in \[0, 1\] or none"),
        ({"model_size": "12parsec"}, "model_size"),
        ({"samples": True}, "samples: expected an integer"),
    ],
)
def test_bad_parameters_are_value_errors_with_the_librarys_messages(sphere, parameters, message):
    with pytest.raises(ValueError, match=message):
        meander.curve(sphere, **parameters)


def test_an_unknown_parameter_is_a_type_error(sphere):
    with pytest.raises(TypeError, match="curve\\(\\) got an unexpected keyword argument 'spacng'"):
        meander.curve(sphere, spacng=3)
    with pytest.raises(TypeError, match="duotone\\(\\) got an unexpected keyword argument 'radius'"):
        meander.duotone(sphere, radius=3)


def test_every_parameter_is_described_as_the_command_line_has_it(cli):
    for job in ["curve", "wire", "duotone"]:
        described = meander.parameters(job)
        names = [p["name"] for p in described]
        assert len(names) == len(set(names))
        helptext = subprocess.run([cli, job, "--help"], check=True, capture_output=True, text=True).stdout
        for p in described:
            assert "--" + p["name"].replace("_", "-") in helptext
            assert p["help"] and p["default"] is not None
    assert {"name": "samples", "min": 1.0, "max": 1000.0, "default": "4"}.items() <= next(
        p for p in meander.parameters("curve") if p["name"] == "samples").items()


def test_files_that_cannot_be_read_are_os_errors_and_malformed_ones_mesh_errors(tmp_path):
    with pytest.raises(OSError, match="missing.obj"):
        meander.read(tmp_path / "missing.obj")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(meander.MeshError, match="bad.obj:4"):
        meander.read(bad)
    assert issubclass(meander.MeshError, ValueError)


def test_a_mesh_that_needs_repair_is_repaired_with_a_warning_or_refused_when_strict():
    # Three triangles on one edge: a non-manifold edge.
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=np.float32)
    fan = meander.Mesh(vertices, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(meander.MeshError, match="^mesh: "):
        meander.curve(fan, strict=True)
    with pytest.warns(meander.MeshWarning, match="mesh: repaired: "):
        curves = meander.curve(fan)
    assert len(curves) >= 1


def test_a_topology_the_job_refuses_is_a_mesh_error_naming_the_mesh(sphere):
    with pytest.raises(meander.MeshError, match="^sphere: .*quad"):
        meander.curve(sphere, quad="none")


def test_a_callback_that_raises_cancels_the_job_and_its_exception_comes_back(sphere):
    stages = []

    def stop(stage, fraction):
        stages.append((stage, fraction))
        raise KeyError("stopped by the caller")

    meander._hold_next_job()  # the job waits at its first check until cancelled
    with pytest.raises(KeyError, match="stopped by the caller"):
        meander.curve(sphere, progress=stop)
    assert len(stages) == 1 and isinstance(stages[0][0], str) and stages[0][0]
    # The module still works after a cancelled job.
    assert len(meander.curve(sphere)) == 1


def test_no_warning_on_a_clean_mesh(sphere):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        meander.curve(sphere)


def test_the_documented_example_runs_and_prints_what_the_docs_say(tmp_path):
    example = pathlib.Path(__file__).parents[2] / "examples" / "python_example.py"
    run = subprocess.run([sys.executable, str(example)], cwd=tmp_path, check=True, capture_output=True, text=True)
    assert run.stdout.split("\n")[:3] == ["1 (76800, 3) float32", "True 1.15", "96"]
    assert (tmp_path / "pretzel_curve.png").exists() and (tmp_path / "pretzel_wire.stl").exists()


def test_draw_makes_the_command_lines_drawing(sphere, cli, tmp_path):
    path, svg_path = tmp_path / "sphere.obj", tmp_path / "drawing.svg"
    meander.write_mesh(path, sphere)
    subprocess.run([cli, "draw", str(path), "-o", str(svg_path), "--paper", "A5", "--seed", "2", "--pen", "0.5mm"],
                   check=True, capture_output=True)
    paths, svg = meander.draw(meander.read(path), paper="A5", seed=2, pen="0.5mm")
    assert svg == svg_path.read_text()
    assert len(paths) == svg.count("<path") > 0
    points = np.concatenate(paths)
    assert points.dtype == np.float64 and points.shape[1] == 2
    assert points.min(axis=0).tolist() >= [10 - 1e-9, 10 - 1e-9] and (points.max(axis=0) <= [138 + 1e-9, 200 + 1e-9]).all()


def test_image_makes_the_command_lines_drawing_from_a_file_or_an_array(cli, tmp_path):
    picture = meander.render(meshes=meander.generate("torus", 2000), size="120x90", view="top")
    png, svg_path, duotone_path = tmp_path / "torus.png", tmp_path / "torus.svg", tmp_path / "torus.duotone.svg"
    meander.write_png(png, picture)
    subprocess.run([cli, "image", str(png), "-o", str(svg_path), "--duotone", str(duotone_path), "--paper", "A5",
                    "--spacing", "0.8mm", "--seed", "4"], check=True, capture_output=True)
    paths, svg, duotone = meander.image(png, paper="A5", spacing="0.8mm", seed=4)
    assert svg == svg_path.read_text() and duotone == duotone_path.read_text()
    assert meander.image(picture, paper="A5", spacing=0.8, seed=4)[1] == svg
    assert meander.image(picture / 255.0, paper="A5", spacing=0.8, seed=4)[1] == svg  # numbers in 0..1
    assert meander.image(picture.astype(np.int64), paper="A5", spacing=0.8, seed=4)[1] == svg  # other integers as bytes
    assert len(paths) == 1 and np.array_equal(paths[0][0], paths[0][-1])  # one closed line
    assert paths[0].min() >= 10 and (paths[0].max(axis=0) <= [200, 138]).all()  # inside the margins of A5 turned
    assert [p["name"] for p in meander.parameters("image")][:4] == ["paper", "margin", "width", "pen"]
    with pytest.raises(ValueError, match="more than the 100 allowed"):
        meander.image(picture, max_pixels=100)
    with pytest.raises(ValueError, match=r"expected an \(H, W\)"):
        meander.image(np.zeros((4, 4, 2)))
    with pytest.raises(ValueError, match="1x1 pixels"):
        meander.image(np.zeros((1, 1)))


def test_curves_behind_their_occluder_are_not_drawn(sphere):
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    far = np.stack([0.8 * np.cos(t), 0.8 * np.sin(t), np.full_like(t, -0.6)], axis=1)
    paths, _ = meander.draw([far], occluder=meander.generate("sphere", 8000), view="front")
    assert paths == []
    paths, _ = meander.draw(far, view="front")
    assert len(paths) == 1 and np.array_equal(paths[0][0], paths[0][-1])  # closed: back to its first point
    with pytest.raises(ValueError, match="paper 'B7'"):
        meander.draw(far, paper="B7")
    with pytest.raises(TypeError, match="need a mesh"):
        meander.draw(far, seed=3)
