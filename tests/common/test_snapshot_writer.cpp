// Tests for common/io: atomic file replacement, the HDF5 wrapper and HDF5 + XDMF snapshot series.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/io/atomic_file.h"
#include "common/io/hdf5_file.h"
#include "common/io/snapshot_writer.h"

namespace fs = std::filesystem;
using cosim::io::Center;
using cosim::io::FieldView;
using cosim::io::Hdf5File;
using cosim::io::Hdf5Shape;
using cosim::io::SnapshotSeries;
using cosim::io::UniformGrid;
using cosim::io::UnstructuredGrid;

namespace {

// A fresh directory per test, removed afterwards.
class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / fmt::format("cosim_io_{}_{}_{}", info->test_suite_name(), info->name(), ::getpid());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

using AtomicFileTest = IoTest;
using Hdf5FileTest = IoTest;
using SnapshotSeriesTest = IoTest;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t count_occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool any_tmp_file(const fs::path& dir) {
  for (const auto& name : files_in(dir)) {
    if (name.ends_with(".tmp")) return true;
  }
  return false;
}

// Minimal well-formedness check: tags nest properly. Returns "" or a description of the problem.
std::string check_xml_nesting(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    const std::size_t end = xml.find('>', pos);
    if (end == std::string::npos) return "unterminated tag";
    const std::string tag = xml.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (tag.starts_with('?') || tag.starts_with('!')) continue;
    if (tag.starts_with('/')) {
      if (open.empty() || open.back() != tag.substr(1)) return "unexpected </" + tag.substr(1) + ">";
      open.pop_back();
    } else if (!tag.ends_with('/')) {
      open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

// Parses the .xmf with Python's xml.etree (when available) and checks the temporal collection.
void check_xdmf_with_python(const fs::path& xmf, std::size_t snapshots) {
  if (!fs::exists("/usr/bin/python3")) return;
  const std::string script =
      "import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
      "assert r.tag == 'Xdmf' and r.get('Version') == '3.0'; "
      "c = r.find('Domain/Grid'); assert c.get('CollectionType') == 'Temporal'; "
      "assert len(c.findall('Grid')) == int(sys.argv[2]); "
      "assert all(g.find('Time') is not None for g in c.findall('Grid'))";
  const std::string cmd = fmt::format("/usr/bin/python3 -c \"{}\" '{}' {}", script, xmf.string(), snapshots);
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

std::vector<double> iota_values(std::size_t n, double start) {
  std::vector<double> v(n);
  std::iota(v.begin(), v.end(), start);
  return v;
}

// 2-component interleaved vectors (i, -i) -> stored as (i, -i, 0).
std::vector<double> vec2_values(std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) {
    v.push_back(static_cast<double>(i));
    v.push_back(-static_cast<double>(i));
  }
  return v;
}

std::vector<double> padded_vec2(std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) {
    v.push_back(static_cast<double>(i));
    v.push_back(-static_cast<double>(i));
    v.push_back(0.0);
  }
  return v;
}

void expect_root_attributes(const Hdf5File& h5, double time, std::int64_t step) {
  EXPECT_EQ(h5.read_double_attribute("/", "time"), std::vector<double>{time});
  EXPECT_EQ(h5.read_int64_attribute("/", "step"), std::vector<std::int64_t>{step});
  EXPECT_EQ(h5.read_string_attribute("/", "format"), "cosim-snapshot-1");
}

// ------------------------------------------------------------------------------------------ atomic file

TEST(AtomicFile, TempPathIsInTheSameDirectory) {
  EXPECT_EQ(cosim::io::temp_path_for("/a/b/run.xmf"), fs::path("/a/b/run.xmf.tmp"));
  EXPECT_EQ(cosim::io::temp_path_for("run.xmf"), fs::path("run.xmf.tmp"));
  EXPECT_THROW(cosim::io::temp_path_for("/a/b/"), std::invalid_argument);
}

TEST_F(AtomicFileTest, WritesAndReplacesContent) {
  const fs::path p = dir_ / "index.xmf";
  cosim::io::write_file_atomically(p, "first");
  EXPECT_EQ(read_text(p), "first");
  cosim::io::write_file_atomically(p, "second, longer content");
  EXPECT_EQ(read_text(p), "second, longer content");
  cosim::io::write_file_atomically(p, "");
  EXPECT_EQ(read_text(p), "");
  EXPECT_FALSE(any_tmp_file(dir_));
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsWithPath) {
  const fs::path p = dir_ / "missing" / "index.xmf";
  try {
    cosim::io::write_file_atomically(p, "x");
    FAIL() << "expected an exception";
  } catch (const std::system_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "missing").string()), std::string::npos) << e.what();
  }
}

// Works as root too: a directory in the way of the temporary file makes the write fail.
TEST_F(AtomicFileTest, FailedTempWriteKeepsOldContent) {
  const fs::path p = dir_ / "index.xmf";
  cosim::io::write_file_atomically(p, "old");
  fs::create_directories(cosim::io::temp_path_for(p) / "blocker");
  EXPECT_THROW(cosim::io::write_file_atomically(p, "new"), std::system_error);
  EXPECT_EQ(read_text(p), "old");
}

TEST_F(AtomicFileTest, ReadOnlyDirectoryKeepsOldContent) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path p = dir_ / "index.xmf";
  cosim::io::write_file_atomically(p, "old");
  fs::permissions(dir_, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  EXPECT_THROW(cosim::io::write_file_atomically(p, "new"), std::system_error);
  fs::permissions(dir_, fs::perms::owner_write, fs::perm_options::add);
  EXPECT_EQ(read_text(p), "old");
  EXPECT_FALSE(any_tmp_file(dir_));
}

// ------------------------------------------------------------------------------------------ HDF5 wrapper

TEST_F(Hdf5FileTest, RoundTripsDatasetsAndAttributes) {
  const fs::path p = dir_ / "data.h5";
  const std::vector<double> values = iota_values(6, 0.5);
  const std::vector<std::int64_t> ids{7, -3, 1LL << 40, 0};
  const std::array<double, 3> origin{1.0, 2.0, 3.0};
  {
    Hdf5File h5(p, Hdf5File::Mode::Create);
    h5.create_group("/g");
    h5.write_dataset("/g/values", values, Hdf5Shape{2, 3});
    h5.write_dataset("/ids", ids, Hdf5Shape{4});
    h5.write_attribute("/", "time", 1.25);
    h5.write_attribute("/", "time", 2.5);  // replaces
    h5.write_attribute("/g", "step", std::int64_t{42});
    h5.write_attribute("/g", "origin", std::span<const double>(origin));
    h5.write_attribute("/g/values", "units", std::string_view("kg/m^3"));
    h5.close();
    EXPECT_FALSE(h5.is_open());
  }
  const Hdf5File h5(p, Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(h5.dataset_shape("/g/values"), (Hdf5Shape{2, 3}));
  EXPECT_EQ(h5.read_doubles("/g/values"), values);
  EXPECT_EQ(h5.dataset_shape("/ids"), Hdf5Shape{4});
  EXPECT_EQ(h5.read_int64s("/ids"), ids);
  EXPECT_EQ(h5.read_double_attribute("/", "time"), std::vector<double>{2.5});
  EXPECT_EQ(h5.read_int64_attribute("/g", "step"), std::vector<std::int64_t>{42});
  EXPECT_EQ(h5.read_double_attribute("/g", "origin"), std::vector<double>(origin.begin(), origin.end()));
  EXPECT_EQ(h5.read_string_attribute("/g/values", "units"), "kg/m^3");
  EXPECT_TRUE(h5.exists("/"));
  EXPECT_TRUE(h5.exists("/g/values"));
  EXPECT_FALSE(h5.exists("/g/missing"));
  EXPECT_FALSE(h5.exists("/nothing/below"));
}

TEST_F(Hdf5FileTest, ErrorsNameFileAndObject) {
  const fs::path p = dir_ / "data.h5";
  Hdf5File h5(p, Hdf5File::Mode::Create);
  const std::vector<double> v{1.0, 2.0};
  try {
    h5.write_dataset("/no_group/rho", v, Hdf5Shape{2});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("/no_group/rho"), std::string::npos) << msg;
  }
  EXPECT_THROW(h5.write_dataset("/rho", v, Hdf5Shape{3}), std::invalid_argument);
  h5.write_dataset("/rho", v, Hdf5Shape{2});
  EXPECT_THROW(h5.write_dataset("/rho", v, Hdf5Shape{2}), std::runtime_error);  // exists already
  EXPECT_THROW((void)h5.read_doubles("/missing"), std::runtime_error);
  EXPECT_THROW((void)h5.read_string_attribute("/", "missing"), std::runtime_error);
  h5.close();
  EXPECT_THROW(h5.create_group("/late"), std::runtime_error);

  const fs::path missing = dir_ / "missing.h5";
  try {
    Hdf5File in(missing, Hdf5File::Mode::ReadOnly);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------------------------------ snapshots

TEST_F(SnapshotSeriesTest, Uniform1D) {
  SnapshotSeries series(dir_, "line");
  const UniformGrid g{1, {8, 0, 0}, {-1.0, 0.0, 0.0}, {0.25, 0.0, 0.0}};
  const auto rho = iota_values(8, 1.0);
  const auto phi = iota_values(9, 100.0);
  const fs::path h5_path =
      series.write(0.5, 10, g, {{"density", rho.data(), 1, Center::Cell}, {"potential", phi.data(), 1, Center::Node}});
  EXPECT_EQ(h5_path, dir_ / "line_000000.h5");

  const Hdf5File h5(h5_path, Hdf5File::Mode::ReadOnly);
  expect_root_attributes(h5, 0.5, 10);
  EXPECT_EQ(h5.read_string_attribute("/grid", "type"), "uniform");
  EXPECT_EQ(h5.read_int64_attribute("/grid", "dim"), std::vector<std::int64_t>{1});
  EXPECT_EQ(h5.read_int64_attribute("/grid", "cells"), (std::vector<std::int64_t>{8, 1, 1}));
  EXPECT_EQ(h5.read_double_attribute("/grid", "origin"), (std::vector<double>{-1.0, 0.0, 0.0}));
  EXPECT_EQ(h5.read_double_attribute("/grid", "spacing"), (std::vector<double>{0.25, 1.0, 1.0}));
  EXPECT_EQ(h5.dataset_shape("/cell/density"), Hdf5Shape{8});
  EXPECT_EQ(h5.read_doubles("/cell/density"), rho);
  EXPECT_EQ(h5.dataset_shape("/node/potential"), Hdf5Shape{9});
  EXPECT_EQ(h5.read_doubles("/node/potential"), phi);

  const std::string xmf = read_text(dir_ / "line.xmf");
  EXPECT_NE(xmf.find("TopologyType=\"3DCoRectMesh\" Dimensions=\"1 1 9\""), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">0 0 -1</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">1 1 0.25</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("Dimensions=\"8\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                     "line_000000.h5:/cell/density<"),
            std::string::npos)
      << xmf;
  EXPECT_NE(xmf.find("Center=\"Node\""), std::string::npos);
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

TEST_F(SnapshotSeriesTest, Uniform2DStoresVectorsWithThreeComponents) {
  SnapshotSeries series(dir_, "plane");
  const UniformGrid g{2, {4, 3, 0}, {0.0, 0.0, 0.0}, {0.1, 0.2, 0.0}};
  const auto rho = iota_values(12, 0.0);
  const auto vel = vec2_values(12);
  const auto node_vel = vec2_values(20);
  const fs::path h5_path = series.write(1.0, 3, g,
                                        {{"rho", rho.data(), 1, Center::Cell},
                                         {"velocity", vel.data(), 2, Center::Cell},
                                         {"velocity", node_vel.data(), 2, Center::Node}});
  const Hdf5File h5(h5_path, Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(h5.dataset_shape("/cell/rho"), (Hdf5Shape{3, 4}));
  EXPECT_EQ(h5.read_doubles("/cell/rho"), rho);
  EXPECT_EQ(h5.dataset_shape("/cell/velocity"), (Hdf5Shape{3, 4, 3}));
  EXPECT_EQ(h5.read_doubles("/cell/velocity"), padded_vec2(12));
  EXPECT_EQ(h5.dataset_shape("/node/velocity"), (Hdf5Shape{4, 5, 3}));
  EXPECT_EQ(h5.read_doubles("/node/velocity"), padded_vec2(20));

  const std::string xmf = read_text(dir_ / "plane.xmf");
  EXPECT_NE(xmf.find("Dimensions=\"1 4 5\""), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Cell\">"), std::string::npos);
  EXPECT_NE(xmf.find("Dimensions=\"3 4 3\""), std::string::npos) << xmf;
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

// A 2D grid with cell data only is indexed as a slab one smallest cell thick around z = 0 (ParaView's default view
// and both XDMF readers show it); the datasets keep their 2D shape.
TEST_F(SnapshotSeriesTest, Uniform2DCellDataIsIndexedAsASlabOneCellThick) {
  SnapshotSeries series(dir_, "slab");
  const UniformGrid g{2, {4, 3, 0}, {0.0, 0.0, 0.0}, {0.1, 0.2, 0.0}};
  const auto rho = iota_values(12, 0.0);
  const auto vel = vec2_values(12);
  const fs::path h5_path =
      series.write(1.0, 3, g, {{"rho", rho.data(), 1, Center::Cell}, {"velocity", vel.data(), 2, Center::Cell}});
  const Hdf5File h5(h5_path, Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(h5.dataset_shape("/cell/rho"), (Hdf5Shape{3, 4}));
  EXPECT_EQ(h5.read_double_attribute("/grid", "spacing"), (std::vector<double>{0.1, 0.2, 1.0}));
  const std::string xmf = read_text(dir_ / "slab.xmf");
  EXPECT_NE(xmf.find("TopologyType=\"3DCoRectMesh\" Dimensions=\"2 4 5\""), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">-0.05 0 0</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">0.1 0.2 0.1</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(
      xmf.find("Dimensions=\"1 3 4\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">slab_000000.h5:/cell/rho<"),
      std::string::npos)
      << xmf;
  EXPECT_NE(xmf.find("Dimensions=\"1 3 4 3\""), std::string::npos) << xmf;
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

TEST_F(SnapshotSeriesTest, Uniform3D) {
  SnapshotSeries series(dir_, "box");
  const UniformGrid g{3, {2, 3, 4}, {0.0, 1.0, 2.0}, {0.5, 0.25, 0.125}};
  const auto e = iota_values(24, 0.0);
  const auto vel = iota_values(24 * 3, 0.0);
  const auto stress = iota_values(24 * 6, 0.0);
  const auto tnode = iota_values(60, 0.0);
  const fs::path h5_path = series.write(2.0, 7, g,
                                        {{"energy", e.data(), 1, Center::Cell},
                                         {"velocity", vel.data(), 3, Center::Cell},
                                         {"stress", stress.data(), 6, Center::Cell},
                                         {"temperature", tnode.data(), 1, Center::Node}});
  const Hdf5File h5(h5_path, Hdf5File::Mode::ReadOnly);
  expect_root_attributes(h5, 2.0, 7);
  EXPECT_EQ(h5.dataset_shape("/cell/energy"), (Hdf5Shape{4, 3, 2}));
  EXPECT_EQ(h5.read_doubles("/cell/energy"), e);
  EXPECT_EQ(h5.dataset_shape("/cell/velocity"), (Hdf5Shape{4, 3, 2, 3}));
  EXPECT_EQ(h5.read_doubles("/cell/velocity"), vel);
  EXPECT_EQ(h5.dataset_shape("/cell/stress"), (Hdf5Shape{4, 3, 2, 6}));
  EXPECT_EQ(h5.dataset_shape("/node/temperature"), (Hdf5Shape{5, 4, 3}));
  EXPECT_EQ(h5.read_doubles("/node/temperature"), tnode);

  const std::string xmf = read_text(dir_ / "box.xmf");
  EXPECT_NE(xmf.find("Dimensions=\"5 4 3\""), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">2 1 0</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find(">0.125 0.25 0.5</DataItem>"), std::string::npos) << xmf;
  EXPECT_NE(xmf.find("AttributeType=\"Tensor6\""), std::string::npos);
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

// Two quads side by side; the mesh moves between snapshots (Lagrangian).
TEST_F(SnapshotSeriesTest, Unstructured2DMovingMesh) {
  SnapshotSeries series(dir_, "quads");
  std::vector<double> coords{0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1};
  const std::vector<std::int64_t> conn{0, 1, 4, 3, 1, 2, 5, 4};
  const std::vector<double> p{1.5, 2.5};
  const auto vel = vec2_values(6);
  const UnstructuredGrid g{2, coords.data(), 6, conn.data(), 2, 4};
  const std::vector<FieldView> fields{{"pressure", p.data(), 1, Center::Cell},
                                      {"velocity", vel.data(), 2, Center::Node}};
  const fs::path first = series.write(0.0, 0, g, fields);
  for (std::size_t i = 0; i < coords.size(); i += 2) coords[i] *= 2.0;  // stretch in x
  const fs::path second = series.write(0.1, 5, g, fields);
  EXPECT_EQ(series.count(), 2U);

  const Hdf5File h5a(first, Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(h5a.read_string_attribute("/grid", "type"), "unstructured");
  EXPECT_EQ(h5a.read_string_attribute("/grid", "cell_type"), "quadrilateral");
  EXPECT_EQ(h5a.dataset_shape("/grid/coordinates"), (Hdf5Shape{6, 3}));
  EXPECT_EQ(h5a.read_doubles("/grid/coordinates"),
            (std::vector<double>{0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0}));
  EXPECT_EQ(h5a.dataset_shape("/grid/connectivity"), (Hdf5Shape{2, 4}));
  EXPECT_EQ(h5a.read_int64s("/grid/connectivity"), conn);
  EXPECT_EQ(h5a.dataset_shape("/cell/pressure"), Hdf5Shape{2});
  EXPECT_EQ(h5a.read_doubles("/cell/pressure"), p);
  EXPECT_EQ(h5a.dataset_shape("/node/velocity"), (Hdf5Shape{6, 3}));
  EXPECT_EQ(h5a.read_doubles("/node/velocity"), padded_vec2(6));

  const Hdf5File h5b(second, Hdf5File::Mode::ReadOnly);
  expect_root_attributes(h5b, 0.1, 5);
  EXPECT_EQ(h5b.read_doubles("/grid/coordinates")[15], 4.0);  // node 5 x moved from 2 to 4

  const std::string xmf = read_text(dir_ / "quads.xmf");
  EXPECT_NE(xmf.find("<Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"2\">"), std::string::npos);
  EXPECT_NE(xmf.find("<Geometry GeometryType=\"XYZ\">"), std::string::npos);
  EXPECT_NE(xmf.find("Dimensions=\"2 4\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">"
                     "quads_000001.h5:/grid/connectivity<"),
            std::string::npos)
      << xmf;
  EXPECT_NE(xmf.find("quads_000001.h5:/grid/coordinates<"), std::string::npos);
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

TEST_F(SnapshotSeriesTest, Unstructured3DHexahedron) {
  SnapshotSeries series(dir_, "hex");
  const std::vector<double> coords{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const std::vector<std::int64_t> conn{0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<double> rho{3.0};
  const auto u = iota_values(24, 0.0);
  const UnstructuredGrid g{3, coords.data(), 8, conn.data(), 1, 8};
  const fs::path h5_path =
      series.write(4.0, 9, g, {{"rho", rho.data(), 1, Center::Cell}, {"u", u.data(), 3, Center::Node}});
  const Hdf5File h5(h5_path, Hdf5File::Mode::ReadOnly);
  EXPECT_EQ(h5.read_string_attribute("/grid", "cell_type"), "hexahedron");
  EXPECT_EQ(h5.read_int64_attribute("/grid", "dim"), std::vector<std::int64_t>{3});
  EXPECT_EQ(h5.dataset_shape("/grid/coordinates"), (Hdf5Shape{8, 3}));
  EXPECT_EQ(h5.read_doubles("/grid/coordinates"), coords);
  EXPECT_EQ(h5.dataset_shape("/grid/connectivity"), (Hdf5Shape{1, 8}));
  EXPECT_EQ(h5.read_int64s("/grid/connectivity"), conn);
  EXPECT_EQ(h5.read_doubles("/cell/rho"), rho);
  EXPECT_EQ(h5.dataset_shape("/node/u"), (Hdf5Shape{8, 3}));
  EXPECT_EQ(h5.read_doubles("/node/u"), u);

  const std::string xmf = read_text(dir_ / "hex.xmf");
  EXPECT_NE(xmf.find("TopologyType=\"Hexahedron\" NumberOfElements=\"1\""), std::string::npos) << xmf;
  EXPECT_EQ(check_xml_nesting(xmf), "");
}

TEST_F(SnapshotSeriesTest, XdmfListsEverySnapshotWithItsTime) {
  SnapshotSeries series(dir_, "run");
  const UniformGrid g{2, {2, 2, 0}, {0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}};
  const auto rho = iota_values(4, 0.0);
  const std::vector<double> times{0.0, 0.125, 1e-3, 2.5};
  for (std::size_t i = 0; i < times.size(); ++i) {
    const fs::path p = series.write(times[i], static_cast<std::int64_t>(i), g, {{"rho", rho.data(), 1, Center::Cell}});
    EXPECT_EQ(p, dir_ / fmt::format("run_{:06}.h5", i));
    EXPECT_TRUE(fs::exists(p));
  }
  EXPECT_EQ(series.count(), times.size());
  EXPECT_EQ(series.xdmf_path(), dir_ / "run.xmf");

  const std::string xmf = read_text(series.xdmf_path());
  EXPECT_TRUE(xmf.starts_with("<?xml"));
  EXPECT_NE(xmf.find("<Xdmf Version=\"3.0\">"), std::string::npos);
  EXPECT_NE(xmf.find("<Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">"), std::string::npos);
  EXPECT_EQ(count_occurrences(xmf, "<Grid "), times.size() + 1);
  EXPECT_EQ(count_occurrences(xmf, "</Grid>"), times.size() + 1);
  EXPECT_EQ(count_occurrences(xmf, "<Time "), times.size());
  std::size_t pos = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {  // in order, each with its own file
    pos = xmf.find(fmt::format("<Grid Name=\"run_{:06}\"", i), pos);
    ASSERT_NE(pos, std::string::npos) << i;
    EXPECT_EQ(xmf.find("<Time Value=\"", pos), xmf.find(fmt::format("<Time Value=\"{}\"/>", times[i]), pos));
    EXPECT_NE(xmf.find(fmt::format("run_{:06}.h5:/cell/rho", i), pos), std::string::npos);
  }
  EXPECT_EQ(check_xml_nesting(xmf), "");
  check_xdmf_with_python(series.xdmf_path(), times.size());
  EXPECT_FALSE(any_tmp_file(dir_));
  EXPECT_EQ(files_in(dir_),
            (std::vector<std::string>{"run.xmf", "run_000000.h5", "run_000001.h5", "run_000002.h5", "run_000003.h5"}));
}

// A second, shorter run into the same directory replaces the first run's series: no snapshot of the
// longer run is left behind, and files that are not this series' numbered snapshots stay.
TEST_F(SnapshotSeriesTest, NewRunRemovesTheEarlierRunsSnapshots) {
  const UniformGrid g{1, {2, 0, 0}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  const auto rho = iota_values(2, 0.0);
  {
    SnapshotSeries first(dir_, "run");
    for (int i = 0; i < 4; ++i) first.write(i, i, g, {{"rho", rho.data(), 1, Center::Cell}});
  }
  for (const char* keep : {"run_00001.h5", "run_0000001.h5", "run_00000x.h5", "other_000003.h5", "run_000003.csv"})
    std::ofstream(dir_ / keep) << "x";
  SnapshotSeries second(dir_, "run");
  second.write(0.5, 0, g, {{"rho", rho.data(), 1, Center::Cell}});
  EXPECT_EQ(files_in(dir_), (std::vector<std::string>{"other_000003.h5", "run.xmf", "run_000000.h5", "run_0000001.h5",
                                                      "run_000003.csv", "run_00000x.h5", "run_00001.h5"}));
  EXPECT_EQ(count_occurrences(read_text(second.xdmf_path()), "<Time "), 1u);
  EXPECT_EQ(Hdf5File(dir_ / "run_000000.h5", Hdf5File::Mode::ReadOnly).read_double_attribute("/", "time"),
            std::vector<double>{0.5});
  EXPECT_EQ(cosim::io::remove_numbered_files(dir_, "run_", ".csv"), 1u);
  // From an index on (what a stopped run wrote after its checkpoint): the earlier ones stay.
  for (const char* f : {"seg_000001.csv", "seg_000002.csv", "seg_000005.csv"}) std::ofstream(dir_ / f) << "x";
  EXPECT_EQ(cosim::io::remove_numbered_files(dir_, "seg_", ".csv", 2), 2u);
  EXPECT_TRUE(fs::exists(dir_ / "seg_000001.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "seg_000002.csv"));
}

TEST_F(SnapshotSeriesTest, MissingDirectoryThrowsWithPath) {
  const fs::path missing = dir_ / "not_there";
  SnapshotSeries series(missing, "run");
  const UniformGrid g{1, {2, 0, 0}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  const std::vector<double> rho{1.0, 2.0};
  try {
    series.write(0.0, 0, g, {{"rho", rho.data(), 1, Center::Cell}});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(series.count(), 0U);
  EXPECT_FALSE(fs::exists(missing));
}

TEST_F(SnapshotSeriesTest, RejectsInvalidInput) {
  EXPECT_THROW(SnapshotSeries(dir_, ""), std::invalid_argument);
  EXPECT_THROW(SnapshotSeries(dir_, "a/b"), std::invalid_argument);
  SnapshotSeries series(dir_, "bad");
  const std::vector<double> v(64, 1.0);
  const UniformGrid g{2, {2, 2, 0}, {0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}};
  EXPECT_THROW(series.write(0.0, 0, UniformGrid{4, {2, 2, 2}, {}, {1, 1, 1}}, {}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, UniformGrid{2, {2, 0, 0}, {}, {1, 1, 1}}, {}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, g, {{"q", v.data(), 4, Center::Cell}}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, g, {{"q", nullptr, 1, Center::Cell}}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, g, {{"a/b", v.data(), 1, Center::Cell}}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, g, {{"q", v.data(), 1, Center::Cell}, {"q", v.data(), 1, Center::Cell}}),
               std::invalid_argument);
  EXPECT_THROW(series.write(std::numeric_limits<double>::quiet_NaN(), 0, g, {}), std::invalid_argument);
  const std::vector<double> coords(12, 0.0);
  const std::vector<std::int64_t> conn{0, 1, 2, 6};  // node 6 does not exist
  EXPECT_THROW(series.write(0.0, 0, UnstructuredGrid{2, coords.data(), 6, conn.data(), 1, 4}, {}),
               std::invalid_argument);
  EXPECT_THROW(series.write(0.0, 0, UnstructuredGrid{3, coords.data(), 6, conn.data(), 1, 4}, {}),
               std::invalid_argument);
  EXPECT_EQ(series.count(), 0U);
  EXPECT_TRUE(files_in(dir_).empty());
}

// A snapshot whose HDF5 file cannot be written leaves no partial file and no .xmf entry.
TEST_F(SnapshotSeriesTest, FailedSnapshotIsNotPublished) {
  SnapshotSeries series(dir_, "run");
  const UniformGrid g{1, {2, 0, 0}, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  const std::vector<double> rho{1.0, 2.0};
  series.write(0.0, 0, g, {{"rho", rho.data(), 1, Center::Cell}});
  const std::string xmf_before = read_text(series.xdmf_path());

  fs::create_directories(dir_ / "run_000001.h5.tmp" / "blocker");  // HDF5 cannot create its temp file
  try {
    series.write(1.0, 1, g, {{"rho", rho.data(), 1, Center::Cell}});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("run_000001.h5.tmp"), std::string::npos) << e.what();
  }
  EXPECT_EQ(series.count(), 1U);
  EXPECT_FALSE(fs::exists(dir_ / "run_000001.h5"));
  EXPECT_EQ(read_text(series.xdmf_path()), xmf_before);
  fs::remove_all(dir_ / "run_000001.h5.tmp");

  fs::create_directories(dir_ / "run.xmf.tmp" / "blocker");  // the index cannot be rewritten
  EXPECT_THROW(series.write(1.0, 1, g, {{"rho", rho.data(), 1, Center::Cell}}), std::system_error);
  EXPECT_EQ(series.count(), 1U);
  EXPECT_FALSE(fs::exists(dir_ / "run_000001.h5"));
  EXPECT_EQ(read_text(series.xdmf_path()), xmf_before);
  fs::remove_all(dir_ / "run.xmf.tmp");

  series.write(1.0, 1, g, {{"rho", rho.data(), 1, Center::Cell}});
  EXPECT_EQ(series.count(), 2U);
  EXPECT_FALSE(any_tmp_file(dir_));
}

}  // namespace
