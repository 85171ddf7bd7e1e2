// Envelope validation, conversions and the scene hash shared with Python.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "common/coupling/scene_hash.h"
#include "common/coupling/wire.h"
#include "coupling_test_util.h"

using namespace cosim::coupling;

namespace {
Faces two_faces() {
  Faces f;
  f.dim = 2;
  f.count = 2;
  f.centre = {0, 0, 1, 0};
  f.normal = {-1, 0, 1, 0};
  f.area = {1, 1};
  f.velocity = {0, 0, 0, 0};
  f.normal_stress = {0, 0};
  f.impedance = {std::numeric_limits<double>::infinity(), 5.0};
  return f;
}
}  // namespace

TEST(CouplingWire, FacesRoundTripAndValidate) {
  pb::Envelope e = make_envelope(Role::Solid, "t", 3, 0.5);
  to_pb(two_faces(), *e.mutable_faces());
  EXPECT_EQ(validate(e), "");
  std::string why;
  auto back = decode(encode(e), why);
  ASSERT_TRUE(back) << why;
  const Faces f = from_pb(back->faces());
  EXPECT_EQ(f.count, 2);
  EXPECT_EQ(f.impedance[0], std::numeric_limits<double>::infinity());
  EXPECT_EQ(back->header().cycle(), 3);
  EXPECT_EQ(back->header().protocol_version(), kProtocolVersion);

  e.mutable_faces()->mutable_normal()->RemoveLast();
  EXPECT_EQ(validate(e), "InterfaceFaces.normal: 3 values, expected dim * count = 4");
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_area(1, std::nan(""));
  EXPECT_EQ(validate(e), "InterfaceFaces.area[1]: nan is not a finite number");
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_impedance(1, -1.0);
  EXPECT_EQ(validate(e), "InterfaceFaces.impedance[1]: -1, expected > 0");
  // Physically invalid geometry is refused naming the field, the face and the value.
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_area(0, -2.0);
  EXPECT_EQ(validate(e), "InterfaceFaces.area[0]: -2, expected > 0 (face 0)");
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_area(1, 0.0);
  EXPECT_EQ(validate(e), "InterfaceFaces.area[1]: 0, expected > 0 (face 1)");
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_normal(2, 0.0);  // face 1's normal (0, 0)
  EXPECT_EQ(validate(e), "InterfaceFaces.normal[2..3]: length 0, expected a unit normal (face 1)");
  to_pb(two_faces(), *e.mutable_faces());
  e.mutable_faces()->set_normal(0, -3.0);
  EXPECT_EQ(validate(e), "InterfaceFaces.normal[0..1]: length 3, expected a unit normal (face 0)");
}

// A normal against its face's vertex orientation (docs/protocol.md: a 2D segment a -> b has the outward normal
// (b_y - a_y, a_x - b_x); 3D faces by the right-hand rule) is refused: a flipped normal turns the load around.
TEST(CouplingWire, FlippedNormalsAgainstTheVertexOrientationAreRefused) {
  Faces f = two_faces();  // x = 0 (normal -x) and x = 1 (normal +x), unit height
  f.nodes_per_face = 2;
  f.vertex_position = {0, 1, 0, 0, 1, 0, 1, 1};
  f.face_vertex = {0, 1, 2, 3};  // (0,1) -> (0,0): outward -x; (1,0) -> (1,1): outward +x
  pb::Envelope e = make_envelope(Role::Solid, "t", 1, 0.0);
  to_pb(f, *e.mutable_faces());
  EXPECT_EQ(validate(e), "");
  f.normal = {-1, 0, -1, 0};  // face 1 flipped
  to_pb(f, *e.mutable_faces());
  EXPECT_EQ(validate(e),
            "InterfaceFaces.normal[2..3]: face 1 has a normal at 180 degrees from the one its vertices give "
            "(face_vertex order), expected the outward normal of docs/protocol.md (flipped normals?)");
  // 3D: a unit quad in z = 0 ordered counter-clockwise seen from +z has the normal +z; -z is refused.
  Faces q;
  q.dim = 3;
  q.count = 1;
  q.centre = {0.5, 0.5, 0};
  q.normal = {0, 0, 1};
  q.area = {1};
  q.velocity = {0, 0, 0};
  q.normal_stress = {0};
  q.impedance = {1};
  q.nodes_per_face = 4;
  q.vertex_position = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  q.face_vertex = {0, 1, 2, 3};
  to_pb(q, *e.mutable_faces());
  EXPECT_EQ(validate(e), "");
  q.normal = {0, 0, -1};
  to_pb(q, *e.mutable_faces());
  EXPECT_NE(validate(e).find("face 0 has a normal at 180 degrees"), std::string::npos) << validate(e);
}

TEST(CouplingWire, SamplesAndDtValidation) {
  pb::Envelope e = make_envelope(Role::Fluid, "t", 0, 0.0);
  FluidSamples s;
  s.count = 2;
  s.phases = 2;
  s.alpha = s.rho = s.normal_velocity = s.pressure = s.impedance = std::vector<double>(4, 1.0);
  s.wetted = {1, 1};
  to_pb(s, *e.mutable_samples());
  EXPECT_EQ(validate(e), "");
  e.mutable_samples()->mutable_pressure()->Add(1.0);
  EXPECT_EQ(validate(e), "FluidSamples.pressure: 5 values, expected count * phases = 4");
  // Physically invalid states: a volume fraction outside [0, 1], a negative density or impedance.
  for (const auto& [field, index, value, expected] : std::vector<std::tuple<std::string, int, double, std::string>>{
           {"alpha", 3, 1.5, "FluidSamples.alpha[3]: 1.5, expected a volume fraction in [0, 1] (face 1, phase 1)"},
           {"alpha", 0, -0.1, "FluidSamples.alpha[0]: -0.1, expected a volume fraction in [0, 1] (face 0, phase 0)"},
           {"rho", 2, -1.0, "FluidSamples.rho[2]: -1, expected a density >= 0 (face 1, phase 0)"},
           {"impedance", 1, -5.0, "FluidSamples.impedance[1]: -5, expected >= 0 (face 0, phase 1)"}}) {
    FluidSamples bad = s;
    (field == "alpha" ? bad.alpha : field == "rho" ? bad.rho : bad.impedance)[index] = value;
    to_pb(bad, *e.mutable_samples());
    EXPECT_EQ(validate(e), expected);
  }
  // Pressures against what each phase's EOS admits (Hello.phase_min_pressure), on wetted faces only.
  FluidSamples low = s;
  low.pressure[3] = -2e5;
  to_pb(low, *e.mutable_samples());
  EXPECT_EQ(validate(e), "");
  const std::vector<std::string> names{"water", "air"};
  EXPECT_EQ(validate_sample_pressures(e.samples(), {-6e8, 0.0}, names),
            "FluidSamples.pressure[3]: -200000 Pa, below the lowest pressure phase 'air' admits (0 Pa, "
            "Hello.phase_min_pressure) (face 1, phase 1)");
  EXPECT_EQ(validate_sample_pressures(e.samples(), {-6e8, -6e8}, names), "");
  EXPECT_EQ(validate_sample_pressures(e.samples(), {}, names), "");  // no bounds given: no check
  low.wetted = {1, 0};
  to_pb(low, *e.mutable_samples());
  EXPECT_EQ(validate_sample_pressures(e.samples(), {-6e8, 0.0}, names), "");  // nothing sampled at face 1
  pb::Envelope d = make_envelope(Role::Fluid, "t", 0, 0.0);
  d.mutable_dt_proposal()->set_dt(0.0);
  EXPECT_EQ(validate(d), "DtProposal.dt: 0, expected a finite number > 0");
}

TEST(CouplingWire, GarbageIsNotAnEnvelope) {
  std::string why;
  EXPECT_FALSE(decode(std::string("\xff\xff\xff", 3), why));
  EXPECT_EQ(why, "malformed message (3 bytes): not a cosim Envelope");
  EXPECT_FALSE(decode("", why));  // parses, but has no header
  EXPECT_EQ(why, "malformed message (0 bytes): Envelope.header missing");
}

TEST(CouplingWire, SceneHashIsStableAndSharedWithPython) {
  EXPECT_EQ(scene_hash_of_text("", {}), "cbf29ce484222325");
  const auto dir = cosim::test::test_dir("hash");
  const auto scene = dir / "s.yaml";
  std::ofstream(scene) << "coupling: {time: {end: 1}}\n";
  const std::string cpp = scene_hash(scene.string(), {"a.b=1"});
  EXPECT_NE(cpp, scene_hash(scene.string(), {}));
  const std::string cmd = "cd " + cosim::test::python_dir().string() +
                          " && /usr/bin/python3 -c \"import cosim_client as c; print(c.scene_hash('" + scene.string() +
                          "', ['a.b=1']))\"";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[64] = {};
  ASSERT_NE(fgets(buf, sizeof buf, p), nullptr);
  pclose(p);
  EXPECT_EQ(std::string(buf), cpp + "\n");
}
