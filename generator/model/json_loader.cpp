// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/json_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "model/joint_expansion.hpp"
#include "model/json_document.hpp"
#include "model/model_check.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"
#include "model/schema.hpp"

namespace kanegen::model {
namespace {

// Ordered, so that parameters keep the file's order (they become Params fields).
using json = nlohmann::ordered_json;

/// Turns the schema-valid document into a Model. The schema has checked the
/// types and keys; this adds the rules a schema cannot say well.
class JsonReader {
 public:
  JsonReader(json document, std::string file) : doc_(std::move(document)), file_(std::move(file)) {}

  Model read() {
    Model m;
    m.source_file = file_;
    m.name = doc_["name"].get<std::string>();
    check_code_identifier(m.name, "/name", "model name");
    read_parameters(m);
    m.gravity = vec3(doc_, "gravity", "", {0.0, 0.0, -9.81});
    for (std::size_t i = 0; i < doc_["bodies"].size(); ++i) m.bodies.push_back(body(i));
    for (std::size_t i = 0; i < doc_["joints"].size(); ++i) m.joints.push_back(joint(i));
    if (doc_.contains("forces"))
      for (std::size_t i = 0; i < doc_["forces"].size(); ++i) read_force(m, i);
    if (doc_.contains("loops"))
      for (std::size_t i = 0; i < doc_["loops"].size(); ++i) m.loops.push_back(loop(i));
    if (doc_.contains("outputs"))
      for (std::size_t i = 0; i < doc_["outputs"].size(); ++i) m.outputs.push_back(output(i));
    return m;
  }

 private:
  [[noreturn]] void error(const std::string& place, const std::string& problem,
                          const std::string& fix) const {
    throw ModelError(file_, place, problem, fix);
  }

  void check_identifier(const std::string& name, const std::string& place, const std::string& what) const {
    if (is_cpp_keyword(name))
      error(place, what + " '" + name + "' is a C++ keyword", "choose another name, e.g. '" + name + "_'");
  }

  /// A name the generated code uses as a C++ identifier (the model's: its
  /// namespace; a parameter's: a field of Params), not only as a string.
  void check_code_identifier(const std::string& name, const std::string& place,
                             const std::string& what) const {
    check_identifier(name, place, what);
    if (is_library_macro(name))
      error(place, what + " '" + name + "' is a macro of the C library headers that generated code includes",
            "choose another name, e.g. '" + name + "_'");
  }

  void read_parameters(Model& m) const {
    if (!doc_.contains("parameters")) return;
    for (const auto& [name, value] : doc_["parameters"].items()) {
      const std::string place = "/parameters/" + pointer_token(name);
      check_code_identifier(name, place, "parameter name");
      if (is_reserved_parameter_name(name))
        error(place, "parameter name '" + name + "' is reserved",
              "rename it: t, q, u, tau, p, pi, I, Pi, Euler, Catalan and the function names are taken");
      m.parameters.push_back({name, value.get<double>(), place});
    }
  }

  static Scalar scalar(const json& v, const std::string& place) {
    if (v.is_string()) return Scalar::expression(v.get<std::string>(), place);
    return Scalar::number(v.get<double>(), place);
  }

  /// parent[key] as a scalar, or `fallback` when absent.
  static Scalar scalar(const json& parent, const std::string& key, const std::string& place,
                       double fallback) {
    const std::string at = place + "/" + key;
    return parent.contains(key) ? scalar(parent[key], at) : Scalar::number(fallback, at);
  }

  static Vec3 vec3(const json& parent, const std::string& key, const std::string& place,
                   const std::array<double, 3>& fallback) {
    const std::string at = place + "/" + key;
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
      const std::string entry = at + "/" + std::to_string(i);
      out[i] = parent.contains(key) ? scalar(parent[key][i], entry) : Scalar::number(fallback[i], entry);
    }
    return out;
  }

  void check_names(const json& item, const std::string& place, const std::string& what) const {
    for (const char* key : {"name", "body", "body2", "parent", "child", "joint"})
      if (item.contains(key))
        check_identifier(item[key].get<std::string>(), place + "/" + key, what + " " + key);
  }

  Body body(std::size_t i) const {
    const json& j = doc_["bodies"][i];
    const std::string place = "/bodies/" + std::to_string(i);
    check_names(j, place, "body");
    Body b;
    b.name = j["name"].get<std::string>();
    b.where = place;
    if (!j.contains("mass") && !j.contains("flexible"))
      error(place, "missing required key 'mass'", "add \"mass\": the mass in kg (or \"flexible\": a beam)");
    b.mass = j.contains("mass") ? scalar(j["mass"], place + "/mass") : Scalar::number(0.0, place + "/mass");
    b.com = vec3(j, "com", place, {0, 0, 0});
    const json inertia = j.value("inertia", json::object());
    const char* keys[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
    for (int k = 0; k < 6; ++k) b.inertia[k] = scalar(inertia, keys[k], place + "/inertia", 0.0);
    if (j.contains("flexible")) {
      b.flexible = true;
      b.elastic = beam(j["flexible"], place + "/flexible");
    }
    return b;
  }

  ElasticPart beam(const json& j, const std::string& place) const {
    if (j.contains("mesh")) return mesh_body(j, place);
    if (!j.contains("section"))
      error(place, "missing required key 'section'",
            "add \"section\": {\"A\": ..., \"Iz\": ...} for a beam, or give a \"mesh\"");
    ElasticPart f;
    f.where = place;
    f.formulation =
        j.value("formulation", "planar") == "spatial" ? BeamFormulation::spatial : BeamFormulation::planar;
    if (j.contains("segments") == j.contains("length"))
      error(place,
            j.contains("length") ? "both 'length' and 'segments' given" : "missing 'length' (or 'segments')",
            "give either \"length\" and \"elements\" (a beam along the body x axis) or \"segments\"");
    const bool assumed = j.contains("assumed_modes");
    if (assumed) read_assumed_modes(j, place, f);
    if (j.contains("length")) {
      // Assumed modes are sampled on an internal mesh, fine unless told otherwise.
      if (!j.contains("elements") && !assumed)
        error(place, "missing required key 'elements'",
              "add \"elements\": the number of finite elements (1 to 200)");
      f.segments.push_back({{j["length"].get<double>(), 0.0, 0.0},
                            j.value("elements", kAssumedModeElements),
                            place + "/length"});
    } else {
      if (j.contains("elements"))
        error(place + "/elements", "'elements' does not apply with 'segments'",
              "give the number of elements of each segment in the segment");
      for (std::size_t i = 0; i < j["segments"].size(); ++i) {
        const json& seg = j["segments"][i];
        BeamSegment s;
        for (int k = 0; k < 3; ++k) s.to[k] = seg["to"][k].get<double>();
        s.elements = seg["elements"].get<int>();
        s.where = place + "/segments/" + std::to_string(i);
        f.segments.push_back(s);
      }
    }
    const json& section = j["section"];
    f.A = section["A"].get<double>();
    f.Iy = section.value("Iy", 0.0);
    f.Iz = section.value("Iz", 0.0);
    f.J = section.value("J", 0.0);
    f.fibre_y = section.value("fibre_y", 0.0);
    f.fibre_z = section.value("fibre_z", 0.0);
    const json& material = j["material"];
    f.E = material["E"].get<double>();
    f.density = material["density"].get<double>();
    if (material.contains("G") && material.contains("poisson"))
      error(place + "/material", "both 'G' and 'poisson' given", "give one of them");
    f.G = material.contains("G")         ? material["G"].get<double>()
          : material.contains("poisson") ? f.E / (2.0 * (1.0 + material["poisson"].get<double>()))
                                         : 0.0;
    const std::string support = j.value("support", "clamped");
    f.support = support == "clamped"         ? BeamSupport::clamped
                : support == "pinned-pinned" ? BeamSupport::pinned_pinned
                                             : BeamSupport::free;
    f.modes = j.value("modes", 0);
    if (j.contains("tip")) {
      f.tip_mass = j["tip"]["mass"].get<double>();
      const json inertia = j["tip"].value("inertia", json::object());
      const char* keys[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
      for (int k = 0; k < 6; ++k) f.tip_inertia[k] = inertia.value(keys[k], 0.0);
    }
    read_damping_and_initial(j, place, f);
    return f;
  }

  /// What beams and mesh bodies share: damping, geometric stiffening, initial values.
  void read_damping_and_initial(const json& j, const std::string& place, ElasticPart& f) const {
    if (j.contains("damping")) {
      const json& d = j["damping"];
      if (d.contains("rayleigh") == d.contains("modal_ratio"))
        error(place + "/damping", "give one of 'rayleigh' and 'modal_ratio'",
              "write {\"rayleigh\": [alpha, beta]} or {\"modal_ratio\": zeta}");
      if (d.contains("rayleigh")) {
        f.rayleigh_alpha = d["rayleigh"][0].get<double>();
        f.rayleigh_beta = d["rayleigh"][1].get<double>();
      } else {
        f.modal_damping = d["modal_ratio"].get<double>();
      }
    }
    f.geometric_stiffening = j.value("geometric_stiffening", true);
    if (j.contains("initial")) {
      // The names are checked against the beam's coordinates by check_model.
      const json& initial = j["initial"];
      if (initial.contains("q"))
        for (const auto& [name, value] : initial["q"].items()) f.initial_q[name] = value.get<double>();
      if (initial.contains("u"))
        for (const auto& [name, value] : initial["u"].items()) f.initial_u[name] = value.get<double>();
    }
  }

  /// A file named in the model, relative to the model file, so that a model
  /// and its data move together.
  std::string relative_to_model(const std::string& name) const {
    const std::filesystem::path given(name);
    return given.is_absolute()
               ? given.string()
               : (std::filesystem::path(file_).parent_path() / given).lexically_normal().string();
  }

  /// A body meshed with plane or solid elements (ElasticPart::mesh).
  ElasticPart mesh_body(const json& j, const std::string& place) const {
    for (const char* key :
         {"length", "elements", "segments", "section", "assumed_modes", "tip", "formulation"})
      if (j.contains(key))
        error(place + "/" + key, std::string("'") + key + "' does not apply to a body given by a mesh",
              "remove it: the mesh gives the shape, and \"mesh\" the element set and thickness");
    ElasticPart f;
    f.where = place;
    const json& m = j["mesh"];
    f.mesh.where = place + "/mesh";
    f.mesh.file = m["file"].get<std::string>();
    f.mesh.path = relative_to_model(f.mesh.file);
    if (m.contains("matrices")) {
      const json& x = m["matrices"];
      f.mesh.matrices.where = f.mesh.where + "/matrices";
      f.mesh.matrices.stiffness = relative_to_model(x["stiffness"].get<std::string>());
      f.mesh.matrices.mass = relative_to_model(x["mass"].get<std::string>());
      f.mesh.matrices.dofs = relative_to_model(x["dofs"].get<std::string>());
    }
    f.mesh.element_set = m.value("element_set", "");
    f.mesh.thickness = m.value("thickness", 1.0);
    const json& material = j["material"];
    f.E = material["E"].get<double>();
    f.density = material["density"].get<double>();
    if (!material.contains("poisson"))
      error(place + "/material", "a mesh body needs Poisson's ratio", "add \"poisson\": nu (0.3 for steel)");
    if (material.contains("G"))
      error(place + "/material/G", "'G' does not apply to a mesh body", "give \"poisson\" only");
    f.mesh.poisson = material["poisson"].get<double>();
    f.G = f.E / (2.0 * (1.0 + f.mesh.poisson));
    const std::string support = j.value("support", "clamped");
    if (support == "pinned-pinned")
      error(place + "/support", "a mesh body is \"clamped\" (on a node set) or \"free\"",
            "use \"support\": \"clamped\" with \"mesh\": {\"clamped_set\": ...}, or \"free\"");
    f.support = support == "free" ? BeamSupport::free : BeamSupport::clamped;
    if (f.support == BeamSupport::clamped && !m.contains("clamped_set"))
      error(f.mesh.where, "a clamped mesh body needs the node set its joint holds",
            "add \"clamped_set\": the name of a node set (*NSET, or a Gmsh physical group) of the mesh, "
            "or give \"support\": \"free\"");
    if (f.support == BeamSupport::free && m.contains("clamped_set"))
      error(f.mesh.where + "/clamped_set", "'clamped_set' does not apply with \"support\": \"free\"",
            "remove it, or set \"support\": \"clamped\"");
    f.mesh.clamped_set = m.value("clamped_set", "");
    f.mesh.craig_bampton = m.value("reduction", "modal") == "craig-bampton";
    if (f.mesh.craig_bampton && f.support == BeamSupport::free)
      error(f.mesh.where + "/reduction", "Craig-Bampton reduction needs a clamped mesh body",
            "give \"support\": \"clamped\" and a \"clamped_set\", or \"reduction\": \"modal\"");
    if (!j.contains("modes"))
      error(place, "a mesh body needs \"modes\"",
            "add \"modes\": k, the number of modes kept (its nodal coordinates would be far too many)");
    f.modes = j["modes"].get<int>();
    read_damping_and_initial(j, place, f);
    // The second-order field of the stiffening is measured from the held set:
    // a free body has none, so its stiffening is off unless asked for, and refused then.
    if (f.support == BeamSupport::free) {
      if (j.value("geometric_stiffening", false))
        error(place + "/geometric_stiffening",
              "geometric stiffening of a free mesh body is not available: its second-order displacement "
              "field needs the body held on a node set",
              "give \"support\": \"clamped\" with a \"clamped_set\" (or Craig-Bampton), or set "
              "\"geometric_stiffening\": false (or leave it out)");
      f.geometric_stiffening = false;
    }
    // Imported matrices carry no element stresses: no geometric stiffness.
    if (f.mesh.matrices.present()) {
      if (j.value("geometric_stiffening", false))
        error(place + "/geometric_stiffening",
              "geometric stiffening of a body whose matrices are imported is not available: the solver's K "
              "and M carry no element stresses for its geometric stiffness",
              "set \"geometric_stiffening\": false (or leave it out), or remove \"matrices\" so that "
              "kanegen assembles the mesh itself");
      f.geometric_stiffening = false;
    }
    if (f.mesh.craig_bampton && f.modal_damping > 0)
      error(place + "/damping",
            "modal damping does not apply to Craig-Bampton coordinates (they are not modes)",
            "give {\"rayleigh\": [alpha, beta]}");
    return f;
  }

  /// The assumed modes; they carry the boundary conditions and are the
  /// coordinates, so `support` and `modes` do not apply, and the shapes are
  /// functions of x along one straight run.
  void read_assumed_modes(const json& j, const std::string& place, ElasticPart& f) const {
    for (const char* key : {"modes", "support"})
      if (j.contains(key))
        error(place + "/" + key, std::string("'") + key + "' does not apply with 'assumed_modes'",
              std::string("remove \"") + key + "\"" +
                  (key == std::string("modes")
                       ? ": the amplitudes of the assumed modes are the coordinates"
                       : ": the shape functions carry the boundary conditions (make them vanish where the "
                         "beam is held)"));
    if (j.contains("segments"))
      error(place + "/segments", "assumed modes need a straight beam along the body x axis",
            "give \"length\" (and optionally \"elements\", the mesh they are sampled on) instead of "
            "\"segments\"");
    const bool planar = f.formulation == BeamFormulation::planar;
    const json& modes = j["assumed_modes"];
    for (std::size_t k = 0; k < modes.size(); ++k) {
      AssumedMode mode;
      mode.where = place + "/assumed_modes/" + std::to_string(k);
      for (const auto& [key, value] : modes[k].items()) {
        if (planar && (key == "w" || key == "theta"))
          error(mode.where + "/" + key,
                "a planar beam has no '" + key + "' (" +
                    (key == "w" ? "bending out of the x-y plane" : "torsion") + ")",
                "remove it, or use \"formulation\": \"spatial\"");
        (key == "u"   ? mode.u
         : key == "v" ? mode.v
         : key == "w" ? mode.w
                      : mode.theta) = value.get<std::string>();
      }
      f.assumed_modes.push_back(mode);
    }
  }

  /// A node given as an index or "tip" (kTipNode, resolved by check_model).
  static int node(const json& v) { return v.is_string() ? kTipNode : v.get<int>(); }

  /// A place on a body is given one way: a point of its frame, a node of a
  /// beam, or a node set of a mesh. `suffix` is "" or "2" (a loop's second
  /// body).
  void check_one_place(const json& j, const std::string& place, const std::string& suffix) const {
    const std::string keys[] = {"point" + suffix, "node" + suffix, "node_set" + suffix};
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        if (j.contains(keys[a]) && j.contains(keys[b]))
          error(place + "/" + keys[b], "both '" + keys[a] + "' and '" + keys[b] + "' given",
                "give one: a point of the body frame, a node of a beam (\"node\"), or a node set of a mesh "
                "body (\"node_set\")");
  }

  /// A joint's initial coordinate and speed: numbers, or for a joint of
  /// several coordinates one number per coordinate (speed) in an array.
  void read_initial(const json& initial, const std::string& place, Joint& out) const {
    const JointTypeInfo& info = joint_type_info(out.type);
    for (const char* key : {"q", "u"}) {
      if (!initial.contains(key)) continue;
      const json& v = initial[key];
      const std::string at = place + "/" + key;
      const bool coordinates = key[0] == 'q';
      if (info.coordinates == 1) {
        if (!v.is_number())
          error(at, std::string(info.name) + " joint '" + out.name + "' has one coordinate",
                "give one number");
        (coordinates ? out.q0 : out.u0) = v.get<double>();
        continue;
      }
      const int count = coordinates ? info.coordinates : info.speeds;
      const std::string what = coordinates || info.speeds == info.coordinates ? " coordinates" : " speeds";
      if (!v.is_array() || v.size() != static_cast<std::size_t>(count))
        error(at, std::string(info.name) + " joint '" + out.name + "' has " + std::to_string(count) + what,
              "give an array of " + std::to_string(count) + " numbers, in the order " +
                  initial_order(info, coordinates));
      std::vector<double>& values = coordinates ? out.step_q0 : out.step_u0;
      for (const json& x : v) values.push_back(x.get<double>());
    }
    if (!out.step_q0.empty()) unit_quaternion(info, place + "/q", out.step_q0);
  }

  /// The order of a joint's initial coordinates (speeds) in a model file.
  static std::string initial_order(const JointTypeInfo& info, bool coordinates) {
    if (info.type == JointType::spherical)
      return coordinates ? "w, x, y, z (a unit quaternion)" : "wx, wy, wz";
    if (info.type == JointType::free)
      return coordinates ? "x, y, z, then the quaternion w, x, y, z" : "x, y, z, then wx, wy, wz";
    return "of its steps (" + step_suffixes(info) + ")";
  }

  /// A spherical joint's quaternion (the last four of a free joint's
  /// coordinates) must have unit length; it is made exactly unit.
  void unit_quaternion(const JointTypeInfo& info, const std::string& at, std::vector<double>& q) const {
    if (info.type != JointType::spherical && info.type != JointType::free) return;
    const std::size_t first = q.size() - 4;
    double norm = 0;
    for (std::size_t k = first; k < q.size(); ++k) norm += q[k] * q[k];
    norm = std::sqrt(norm);
    if (!(std::abs(norm - 1) <= 1e-6))
      error(at, "the quaternion of " + std::string(info.name) + " joint has length " + std::to_string(norm),
            "give a unit quaternion w, x, y, z, e.g. [1, 0, 0, 0] for no turn");
    for (std::size_t k = first; k < q.size(); ++k) q[k] /= norm;
  }

  static std::string step_suffixes(const JointTypeInfo& info) {
    std::string out;
    for (int s = 0; s < info.step_count; ++s) out += (s == 0 ? "" : ", ") + std::string(info.steps[s].suffix);
    return out;
  }

  Joint joint(std::size_t i) const {
    const json& j = doc_["joints"][i];
    const std::string place = "/joints/" + std::to_string(i);
    check_names(j, place, "joint");
    Joint out;
    out.name = j["name"].get<std::string>();
    out.where = place;
    const std::string type = j["type"].get<std::string>();
    // The schema's enum is the table's (model/schema.cpp), so the name is known.
    out.type = joint_type_named(type)->type;
    out.parent = j["parent"].get<std::string>();
    out.child = j["child"].get<std::string>();
    const json origin = j.value("origin", json::object());
    out.origin_xyz = vec3(origin, "xyz", place + "/origin", {0, 0, 0});
    out.origin_rpy = vec3(origin, "rpy", place + "/origin", {0, 0, 0});
    if (!out.moves()) {
      // Fields of a coordinate the fixed joint does not have: likely a mistaken type.
      for (const char* key : {"axis", "spring", "damping", "actuated", "initial"})
        if (j.contains(key))
          error(place + "/" + key,
                "fixed joint '" + out.name + "' has no coordinate, so '" + key + "' does not apply",
                "remove it, or make the joint " + joint_type_list(JointKinds::moving, "or"));
      out.actuated = false;
    }
    if (j.contains("axis") && (out.type == JointType::spherical || out.type == JointType::free))
      error(place + "/axis",
            std::string(joint_type_info(out.type).name) + " joint '" + out.name + "' has no axis",
            "remove it: the joint frame's axes (origin rpy) are those of its motion");
    if (j.contains("axis"))
      for (int k = 0; k < 3; ++k) out.axis[k] = j["axis"][k].get<double>();
    const json spring = j.value("spring", json::object());
    out.spring_stiffness = scalar(spring, "stiffness", place + "/spring", 0.0);
    out.spring_rest = scalar(spring, "rest", place + "/spring", 0.0);
    out.damping = scalar(j, "damping", place, 0.0);
    if (out.moves()) out.actuated = j.value("actuated", true);
    read_initial(j.value("initial", json::object()), place + "/initial", out);
    if (j.contains("parent_node")) out.parent_node = node(j["parent_node"]);
    if (j.contains("parent_node_set")) {
      if (j.contains("parent_node"))
        error(place + "/parent_node_set", "both 'parent_node' and 'parent_node_set' given",
              "give one of them");
      out.parent_node_set = j["parent_node_set"].get<std::string>();
    }
    if (j.contains("independent")) {
      if (!out.moves())
        error(place + "/independent", "fixed joint '" + out.name + "' has no coordinate to be independent",
              "remove it");
      out.independent = j["independent"].get<bool>();
    }
    if (j.contains("prescribed")) {
      const std::string at = place + "/prescribed";
      if (!out.moves())
        error(at, "fixed joint '" + out.name + "' has no coordinate to prescribe", "remove it");
      for (const char* key : {"spring", "damping", "actuated", "initial"})
        if (j.contains(key))
          error(place + "/" + key,
                "'" + std::string(key) + "' does not apply to prescribed joint '" + out.name + "'",
                "remove it: the motion is given by \"prescribed\"");
      out.actuated = false;
      const json& p = j["prescribed"];
      if (p.is_string()) {
        out.prescribed.push_back({p.get<std::string>(), false, 0.0, at});
      } else {
        for (std::size_t i = 0; i < p.size(); ++i) {
          const std::string piece = at + "/" + std::to_string(i);
          const bool last = i + 1 == p.size();
          if (last == p[i].contains("until"))
            error(piece, last ? "the last piece has an 'until'" : "missing 'until'",
                  last ? "remove it: the last piece holds for all later times"
                       : "give the time the piece ends, \"until\": seconds");
          PrescribedPiece x{p[i]["q"].get<std::string>(), !last, last ? 0.0 : p[i]["until"].get<double>(),
                            piece + "/q"};
          if (i > 0 && !last && !(x.until > out.prescribed.back().until))
            error(piece + "/until", "pieces must end at increasing times", "order the pieces by time");
          out.prescribed.push_back(x);
        }
      }
    }
    return out;
  }

  /// One entry of "forces", by its type. The schema lists the keys of all
  /// types; each type takes its own, and a key of another type is a mistake.
  void read_force(Model& m, std::size_t i) const {
    const json& j = doc_["forces"][i];
    const std::string place = "/forces/" + std::to_string(i);
    check_names(j, place, "force");
    const std::string type = j.value("type", "constant");
    struct Key {
      const char* name;
      bool required;
      const char* fix;  ///< for a missing required key
    };
    const std::vector<Key> keys =
        type == "spring"
            ? std::vector<Key>{{"body", true, "add \"body\": the body of the spring's first point"},
                               {"point", false, ""},
                               {"body2", true, "add \"body2\": the body of its second point, or \"ground\""},
                               {"point2", false, ""},
                               {"stiffness", true, "add \"stiffness\": k in N/m"},
                               {"rest_length", false, ""},
                               {"damping", false, ""}}
        : type == "joint_effort"
            ? std::vector<Key>{{"joint", true, "add \"joint\": the name of a moving joint"},
                               {"value", true,
                                "add \"value\": the torque (N m) or force (N), a scalar or an "
                                "expression in the parameters and t"}}
            : std::vector<Key>{{"body", true, "add \"body\": the body it acts on"},
                               {"point", false, ""},
                               {"node", false, ""},
                               {"node_set", false, ""},
                               {"force", true, "add \"force\": [fx, fy, fz] in N"},
                               {"frame", false, ""}};
    for (const Key& key : keys)
      if (key.required && !j.contains(key.name))
        error(place, "missing required key '" + std::string(key.name) + "' for a '" + type + "' force",
              key.fix);
    for (const auto& item : j.items()) {
      const std::string& key = item.key();  // not a structured binding: lambdas cannot capture those in C++17
      if (key == "name" || key == "type") continue;
      if (std::none_of(keys.begin(), keys.end(), [&](const Key& k) { return key == k.name; }))
        error(place + "/" + pointer_token(key), "'" + key + "' does not apply to a '" + type + "' force",
              "remove it (the keys of a constant force: body, point or node or node_set, force, frame. Of a "
              "spring: body, point, body2, point2, stiffness, rest_length, damping. Of a joint_effort: "
              "joint, value)");
    }
    if (type == "spring")
      m.springs.push_back(spring(j, place));
    else if (type == "joint_effort")
      m.joint_efforts.push_back({j["name"].get<std::string>(), j["joint"].get<std::string>(),
                                 scalar(j["value"], place + "/value"), place});
    else
      m.forces.push_back(force(j, place));
  }

  static Spring spring(const json& j, const std::string& place) {
    Spring s;
    s.name = j["name"].get<std::string>();
    s.where = place;
    s.body = j["body"].get<std::string>();
    s.point = vec3(j, "point", place, {0, 0, 0});
    s.body2 = j["body2"].get<std::string>();
    s.point2 = vec3(j, "point2", place, {0, 0, 0});
    s.stiffness = scalar(j["stiffness"], place + "/stiffness");
    s.rest_length = scalar(j, "rest_length", place, 0.0);
    s.damping = scalar(j, "damping", place, 0.0);
    return s;
  }

  PointForce force(const json& j, const std::string& place) const {
    PointForce f;
    f.name = j["name"].get<std::string>();
    f.where = place;
    f.body = j["body"].get<std::string>();
    check_one_place(j, place, "");
    f.point = vec3(j, "point", place, {0, 0, 0});
    if (j.contains("node")) f.node = node(j["node"]);
    f.node_set = j.value("node_set", "");
    f.force = vec3(j, "force", place, {0, 0, 0});
    f.frame = j.value("frame", "world") == "body" ? ForceFrame::body : ForceFrame::world;
    return f;
  }

  Loop loop(std::size_t i) const {
    const json& j = doc_["loops"][i];
    const std::string place = "/loops/" + std::to_string(i);
    check_names(j, place, "loop");
    Loop l;
    l.name = j["name"].get<std::string>();
    l.where = place;
    const std::string type = j["type"].get<std::string>();
    l.type = type == "revolute"    ? LoopType::revolute
             : type == "spherical" ? LoopType::spherical
                                   : LoopType::slider;
    l.planar = j.value("planar", false);
    if (l.planar && l.type == LoopType::spherical)
      error(place + "/planar", "a spherical loop joint cannot be planar",
            "use \"type\": \"revolute\" with \"planar\": true for a hinge of a planar mechanism");
    l.body = j["body"].get<std::string>();
    l.body2 = j["body2"].get<std::string>();
    for (const char* key : {"", "2"}) check_one_place(j, place, key);
    l.point = vec3(j, "point", place, {0, 0, 0});
    l.point2 = vec3(j, "point2", place, {0, 0, 0});
    if (j.contains("node")) l.node = node(j["node"]);
    if (j.contains("node2")) l.node2 = node(j["node2"]);
    l.node_set = j.value("node_set", "");
    l.node_set2 = j.value("node_set2", "");
    if (j.contains("axis")) {
      if (l.type == LoopType::spherical)
        error(place + "/axis", "a spherical loop joint has no axis", "remove \"axis\"");
      for (int k = 0; k < 3; ++k) l.axis[k] = j["axis"][k].get<double>();
    } else if (l.type == LoopType::slider) {
      error(place, "missing required key 'axis' for a slider",
            "add \"axis\": the sliding direction in the frame of '" + l.body + "'");
    }
    return l;
  }

  Output output(std::size_t i) const {
    const json& j = doc_["outputs"][i];
    const std::string place = "/outputs/" + std::to_string(i);
    check_names(j, place, "output");
    Output o;
    o.name = j["name"].get<std::string>();
    o.where = place;
    const std::string type = j["type"].get<std::string>();
    o.kind = type == "point"               ? OutputKind::point_position
             : type == "joint"             ? OutputKind::joint_coordinate
             : type == "joint_speed"       ? OutputKind::joint_speed
             : type == "node_displacement" ? OutputKind::node_displacement
             : type == "axial_force"       ? OutputKind::axial_force
             : type == "bending_moment"    ? OutputKind::bending_moment
             : type == "reaction"          ? OutputKind::reaction
                                           : OutputKind::bending_stress;
    const bool node_output = o.kind != OutputKind::point_position && o.kind != OutputKind::joint_coordinate &&
                             o.kind != OutputKind::joint_speed && o.kind != OutputKind::reaction;
    // Each output type takes its own keys; a key of another type is a mistake.
    // A node output names its node of a beam, or its node set of a mesh body.
    const char* node_key = j.contains("node_set") ? "node_set" : "node";
    const std::vector<std::string> needed =
        o.kind == OutputKind::point_position ? std::vector<std::string>{"body", "point"}
        : node_output                        ? std::vector<std::string>{"body", node_key}
        : o.kind == OutputKind::reaction     ? std::vector<std::string>{"loop"}
                                             : std::vector<std::string>{"joint"};
    for (const std::string& key : needed)
      if (!j.contains(key))
        error(place, "missing required key '" + key + "' for a '" + type + "' output",
              key == "joint"  ? "add \"joint\": the joint name"
              : key == "body" ? "add \"body\": the body name"
              : key == "node" ? "add \"node\": a node index of the flexible body, or \"tip\" (a mesh body: "
                                "\"node_set\": the name of a node set)"
              : key == "loop" ? "add \"loop\": the loop name"
                              : "add \"point\": [x, y, z] in the body frame");
    if (node_output) check_one_place(j, place, "");
    for (const char* key : {"body", "point", "joint", "node", "node_set", "loop"})
      if (j.contains(key) && std::find(needed.begin(), needed.end(), key) == needed.end())
        error(place + "/" + key, "'" + std::string(key) + "' does not apply to a '" + type + "' output",
              "remove it (a point output takes body and point, joint and joint_speed take joint, the node "
              "outputs take body and node (or node_set), reaction takes loop)");
    if (o.kind == OutputKind::point_position) {
      o.body = j["body"].get<std::string>();
      o.point = vec3(j, "point", place, {0, 0, 0});
    } else if (node_output) {
      o.body = j["body"].get<std::string>();
      if (j.contains("node")) o.node = node(j["node"]);
      o.node_set = j.value("node_set", "");
    } else if (o.kind == OutputKind::reaction) {
      o.loop = j["loop"].get<std::string>();
    } else {
      o.joint = j["joint"].get<std::string>();
    }
    return o;
  }

  json doc_;
  std::string file_;
};

}  // namespace

Model load_json_model(const std::string& path) {
  const std::string text = read_text_file(path);
  validate_model_schema(parse_json_document(text, path), path);
  Model model = JsonReader(json::parse(text), path).read();
  expand_compound_joints(model);
  check_model(model, "/");
  return model;
}

}  // namespace kanegen::model
