// Helpers for the io tests: fixture paths, the expectations every encoding of the fixture mesh
// must meet (tests/io/data/make_fixtures.py describes that mesh), and small file utilities.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "mesh/unstructured_mesh.h"
#include "support/test_meshes.h"

namespace sm::io::test {

using sm::test::makeTestMesh;

// tests/io/data/<file>.
std::string fixturePath(const std::string& file);

// The fixture mesh: 13 points, a hexahedron, pyramid, wedge and three tetrahedra (one written
// inverted, one quadratic), a skipped triangle and vertex, clusters 0..3, fields pressure,
// velocity, temp (3 steps), count, time values 0, 0.25, 1.
void expectFixtureMesh(const mesh::UnstructuredMesh& m);
void expectFixtureGeometry(const mesh::UnstructuredMesh& m);  // points, cells, clusters only

// Cells as sortable records (type, cluster, vertex coordinates, field values at the vertices, cell
// data), so that meshes equal up to point and cell order compare equal.
std::vector<std::vector<double>> canonicalCells(const mesh::UnstructuredMesh& m);

// Every element has positive volume (the builder oriented them all).
void expectAllPositive(const mesh::UnstructuredMesh& m);

// Vertex ids of element `i` of type t.
std::vector<uint32_t> cellIds(const mesh::UnstructuredMesh& m, mesh::CellType t, uint64_t i);

// Reads `path`, four tetrahedra on the base (0,0,0), (1,0,0), (0,1,0) with apexes (0,0,1) to
// (0,0,4) and a vtkGhostType cell array flagging one DUPLICATECELL and one HIDDENCELL: expects the
// tetrahedra whose apexes are at `keptApexZ` and one warning for each skipped kind.
void expectGhostCellsSkipped(const std::string& path, std::vector<double> keptApexZ);

std::vector<uint8_t> readBytes(const std::string& path);
void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes);
void writeText(const std::string& path, const std::string& text);

// Small time-series inputs (series_test.cpp, series_checks_test.cpp).
// Two tetrahedra sharing a face, cell array p = (p0, p1), as an ascii .vtu.
std::string twoTets(float p0, float p1);
// The same two tetrahedra with point field f = scale * (0, 1, 2, 3, 4) as a legacy ascii .vtk: a
// format read whole for every step.
std::string legacyTwoTets(float scale);
// Writes DIR/NAME, a .pvd of two steps: FIRST at time 0, SECOND at time 1; returns its path.
std::string twoStepSeries(const std::string& dir, const std::string& name, const std::string& first,
                          const std::string& second);

// The message of the sm::FileError that fn throws; fails the test if it throws nothing or
// something else.
template <class Fn>
std::string fileErrorOf(Fn&& fn);

}  // namespace sm::io::test

#include <gtest/gtest.h>

#include "common/error.h"

namespace sm::io::test {

template <class Fn>
std::string fileErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const FileError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected sm::FileError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected sm::FileError, nothing thrown";
  return {};
}

}  // namespace sm::io::test
