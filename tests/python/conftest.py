"""Shared fixtures of the Python package's tests (run by ctest as `python`, with PYTHONPATH
at the build's python/ folder, MEANDER_CLI the command line and MEANDER_SHARED_MESHES the
real meshes)."""

import os
import pathlib

import numpy as np
import pytest

import meander

SHARED = pathlib.Path(os.environ.get("MEANDER_SHARED_MESHES", pathlib.Path(__file__).parents[3] / "shared" / "meshes"))
CLI = os.environ.get("MEANDER_CLI", "")


@pytest.fixture
def shared():
    """The folder of real meshes; its absence fails under CI, skips elsewhere."""
    if not SHARED.is_dir():
        if os.environ.get("CI"):
            pytest.fail(f"the real meshes are missing: {SHARED} (MEANDER_SHARED_MESHES)")
        pytest.skip(f"no real meshes at {SHARED}")
    return SHARED


@pytest.fixture
def cli():
    """The meander program, to compare the package with."""
    if not CLI or not os.access(CLI, os.X_OK):
        pytest.fail(f"MEANDER_CLI is not the meander program: {CLI!r}")
    return CLI


def components(mesh: meander.Mesh) -> int:
    """The number of connected components of the faces (sharing a vertex), by union-find."""
    parent = np.arange(mesh.num_vertices)

    def root(v):
        while parent[v] != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    offsets, indices = mesh.offsets, mesh.indices
    for f in range(mesh.num_faces):
        corners = indices[offsets[f]:offsets[f + 1]]
        first = root(corners[0])
        for v in corners[1:]:
            parent[root(v)] = first
    used = np.unique(indices)
    return len({root(v) for v in used})


def check_certificate(mesh: meander.Mesh, curves, triangles: meander.Mesh, cycle_start: np.ndarray, samples: int = 4):
    """The cycle's certificate, checked without the library: cycle k is the triangles
    cycle_start[k]:cycle_start[k+1], each sharing an edge (two vertices) with the next and
    the last with the first; no triangle twice; every vertex of the input is one of theirs
    (the dual-simplest quadrangulation keeps them); one cycle and one curve per
    component, each curve `samples` points per triangle."""
    faces = triangles.faces
    assert faces.shape[1] == 3
    assert cycle_start[0] == 0 and cycle_start[-1] == len(faces)
    assert len(cycle_start) - 1 == len(curves) == components(mesh)
    keys = {tuple(sorted(t)) for t in faces.tolist()}
    assert len(keys) == len(faces), "a triangle appears twice"
    for k in range(len(cycle_start) - 1):
        loop = faces[cycle_start[k]:cycle_start[k + 1]]
        following = np.roll(loop, -1, axis=0)
        shared_vertices = (loop[:, :, None] == following[:, None, :]).any(axis=2).sum(axis=1)
        assert (shared_vertices == 2).all(), f"cycle {k}: triangle {int(np.argmin(shared_vertices == 2))} shares no edge with the next"
        assert len(curves[k]) == samples * len(loop)
        assert curves[k].dtype == np.float32 and curves[k].shape[1] == 3
    corners = {tuple(v) for v in triangles.vertices[np.unique(faces)].tolist()}
    assert all(tuple(v) in corners for v in mesh.vertices[np.unique(mesh.indices)].tolist()), "a vertex is not covered"


def check_closed_manifold(faces: np.ndarray):
    """Every edge in exactly two faces, once in each direction (closed, 2-manifold, oriented)."""
    start = faces.astype(np.int64).ravel()
    end = np.roll(faces, -1, axis=1).astype(np.int64).ravel()
    n = int(faces.max()) + 1
    keys = np.sort(start * n + end)
    assert (np.diff(keys) > 0).all(), "a directed edge appears twice: faces misoriented or non-manifold"
    reverse = end * n + start
    assert (keys[np.minimum(np.searchsorted(keys, reverse), len(keys) - 1)] == reverse).all(), \
        "an edge has one face: the mesh is open"
