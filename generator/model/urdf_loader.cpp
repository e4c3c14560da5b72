// SPDX-License-Identifier: GPL-2.0-or-later
#include "model/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "model/joint_expansion.hpp"
#include "model/json_document.hpp"
#include "model/model_check.hpp"
#include "model/model_error.hpp"
#include "model/names.hpp"

namespace kanegen::model {
namespace {

/// A <link> or <joint> child of <robot>, with what the error places need.
struct Element {
  std::string name;
  std::string place;  ///< "line 12: <joint name=\"j3\">"
  const tinyxml2::XMLElement* xml = nullptr;
};

std::string element_place(const tinyxml2::XMLElement* e, const std::string& name) {
  return "line " + std::to_string(e->GetLineNum()) + ": <" + e->Name() +
         (name.empty() ? std::string() : " name=\"" + name + "\"") + ">";
}

/// tinyxml2's "Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=14 (0xe) Line number=4: XMLElement name=link"
/// in words.
std::string xml_error(const tinyxml2::XMLDocument& document) {
  std::string what;
  switch (document.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      what = "an element is not closed, or closed by the wrong tag";
      break;
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      what = "malformed attribute";
      break;
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      what = "malformed element";
      break;
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      what = "the file is empty";
      break;
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      what = "malformed or misplaced <?...?> declaration";
      break;
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      what = "unclosed comment";
      break;
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      what = "malformed text or entity";
      break;
    default:
      what = document.ErrorName();
  }
  const std::string raw = document.ErrorStr();
  const auto line = raw.find("Line number=");
  const auto detail = line == std::string::npos ? std::string::npos : raw.find(": ", line);
  if (detail == std::string::npos) return "malformed XML: " + what;
  // tinyxml2 quotes the text where parsing stopped, which may run over many
  // lines: keep the message one line and short.
  std::string quoted = raw.substr(detail + 2);
  std::replace_if(
      quoted.begin(), quoted.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; }, ' ');
  if (quoted.size() > 80) quoted = quoted.substr(0, 77) + "...";
  return "malformed XML: " + what + " (" + quoted + ")";
}

/// What tinyxml2 gives and urdfdom hides: element order (urdfdom keeps
/// joints in a std::map) and line numbers.
struct UrdfIndex {
  tinyxml2::XMLDocument document;
  std::string robot_place;
  std::vector<Element> links, joints;
};

void index_urdf(const std::string& text, const std::string& file, UrdfIndex& index) {
  if (index.document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw ModelError(file, "line " + std::to_string(index.document.ErrorLineNum()), xml_error(index.document),
                     "fix the XML syntax");
  const tinyxml2::XMLElement* robot = index.document.RootElement();
  if (!robot || std::string(robot->Name()) != "robot")
    throw ModelError(file, robot ? element_place(robot, "") : "line 1", "the root element is not <robot>",
                     "a URDF file holds one <robot> element");
  const char* robot_name = robot->Attribute("name");
  index.robot_place = element_place(robot, robot_name ? robot_name : "");
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "link" && tag != "joint") continue;
    const char* name = e->Attribute("name");
    if (!name || !*name)
      throw ModelError(file, element_place(e, ""), "<" + tag + "> without a name", "add name=\"...\"");
    // Names become CSV columns, JSON keys and string literals of generated
    // code: no control characters, UTF-8 only (docs/errors.md#security).
    if (const std::string problem = name_text_problem(name); !problem.empty())
      throw ModelError(file, element_place(e, name) + "/name", "the " + tag + " name holds " + problem,
                       "rename it: names are UTF-8 text without control characters (newline, tab, NUL, "
                       "escape); letters, digits, '_', '-' and '.' are safe");
    std::vector<Element>& list = tag == "link" ? index.links : index.joints;
    for (const Element& other : list)
      if (other.name == name)
        throw ModelError(file, element_place(e, name),
                         "duplicate " + tag + " name '" + name + "' (also at " +
                             other.place.substr(0, other.place.find(':')) + ")",
                         "rename one of them");
    list.push_back({name, element_place(e, name), e});
  }
}

/// An element kanegen reads (or must see through to the ones it reads): its
/// attributes, the ones that must be there, and its children. A child
/// without an entry of its own is not looked into (<visual>, <collision>).
struct Vocabulary {
  std::vector<std::string> attributes, required, children;
  bool numbers = false;  ///< every attribute is one number (<mass>, <inertia>)
};

const std::map<std::string, Vocabulary>& urdf_vocabulary() {
  static const std::map<std::string, Vocabulary> v = {
      {"robot", {{"name", "version"}, {}, {"link", "joint"}}},
      {"link", {{"name", "type"}, {}, {"inertial", "visual", "collision"}}},
      {"link/inertial", {{}, {}, {"origin", "mass", "inertia"}}},
      {"link/inertial/origin", {{"xyz", "rpy"}, {}, {}}},
      {"link/inertial/mass", {{"value"}, {"value"}, {}, true}},
      {"link/inertial/inertia",
       {{"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}, {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}, {}, true}},
      {"joint",
       {{"name", "type"},
        {},
        {"origin", "parent", "child", "axis", "limit", "dynamics", "calibration", "safety_controller",
         "mimic"}}},
      {"joint/origin", {{"xyz", "rpy"}, {}, {}}},
      {"joint/parent", {{"link"}, {}, {}}},
      {"joint/child", {{"link"}, {}, {}}},
      {"joint/axis", {{"xyz"}, {}, {}}},
      {"joint/limit", {{"lower", "upper", "effort", "velocity"}, {}, {}}},
      {"joint/dynamics", {{"damping", "friction"}, {}, {}}},
      {"joint/calibration", {{"rising", "falling", "reference_position"}, {}, {}}},
      {"joint/safety_controller",
       {{"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}, {}, {}}},
      {"joint/mimic", {{"joint", "multiplier", "offset"}, {}, {}}},
  };
  return v;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known) {
  const std::string guess = nearest(name, known);
  return guess.empty() ? "known here: " + join(known, ", ") : "did you mean '" + guess + "'?";
}

bool is_number(const char* text) {
  char* end = nullptr;
  std::strtod(text, &end);
  while (end && *end != '\0' && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end != text && end && *end == '\0';
}

/// Checks `e` (at `key` in urdf_vocabulary()) and its children: a misspelt
/// element or attribute would otherwise be dropped by urdfdom without a word
/// (<inertia ixxx=...> zeroes the whole inertia, <inertal> the mass).
void check_vocabulary(const tinyxml2::XMLElement* e, const std::string& key, const std::string& place,
                      const std::string& file) {
  const Vocabulary& v = urdf_vocabulary().at(key);
  const std::string here = "line " + std::to_string(e->GetLineNum()) + ": " + place;
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
    const std::string name = a->Name();
    if (key == "robot" && name.rfind("xmlns", 0) == 0) continue;  // namespace declarations
    if (std::find(v.attributes.begin(), v.attributes.end(), name) == v.attributes.end())
      throw ModelError(file, here, "unknown attribute '" + name + "' of <" + e->Name() + ">",
                       did_you_mean(name, v.attributes));
    if (v.numbers && !is_number(a->Value()))
      throw ModelError(file, here + "/" + name, "'" + std::string(a->Value()) + "' is not a number",
                       "write " + name + "=\"...\" as a number (SI units)");
  }
  if (v.numbers && e->GetText() &&
      std::string(e->GetText()).find_first_not_of(" \t\r\n") != std::string::npos)
    throw ModelError(file, here, "<" + std::string(e->Name()) + "> holds text, which URDF ignores",
                     "give the values as attributes: <" + std::string(e->Name()) + " " +
                         join(v.required, "=\"...\" ") + "=\"...\"/>");
  for (const std::string& name : v.required)
    if (!e->Attribute(name.c_str()))
      throw ModelError(file, here, "<" + std::string(e->Name()) + "> has no " + name,
                       "add " + name + "=\"...\"" +
                           (v.required.size() > 1 ? " (all of " + join(v.required, ", ") + ")" : ""));
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string name = c->Name();
    const bool known = std::find(v.children.begin(), v.children.end(), name) != v.children.end();
    // <robot> holds extensions (<mujoco>, <ros2_control>, ...): only a near
    // miss of an element kanegen reads is an error there.
    if (!known && key == "robot" && nearest(name, {"link", "joint"}).empty()) continue;
    if (!known)
      throw ModelError(file, "line " + std::to_string(c->GetLineNum()) + ": " + place + "/" + name,
                       "unknown element <" + name + "> in <" + e->Name() + ">",
                       did_you_mean(name, v.children));
    const std::string child_key = key == "robot" ? name : key + "/" + name;
    if (!urdf_vocabulary().count(child_key)) continue;  // not read by kanegen: <visual>, <material>, ...
    const char* child_name = key == "robot" ? c->Attribute("name") : nullptr;
    const std::string child_place =
        key == "robot" ? "<" + name + (child_name ? " name=\"" + std::string(child_name) + "\"" : "") + ">"
                       : place + "/" + name;
    check_vocabulary(c, child_key, child_place, file);
  }
}

/// The joint type of a URDF type name: the table's names that URDF also
/// has, and URDF's "floating" for the table's free joint; nullptr for
/// another name (the table's spherical and free are no URDF types).
const JointTypeInfo* urdf_joint_type(const std::string& type) {
  if (type == "floating") return &joint_type_info(JointType::free);
  const JointTypeInfo* info = joint_type_named(type);
  if (info && (info->type == JointType::spherical || info->type == JointType::free)) return nullptr;
  return info;
}

/// The type names a URDF may use, in the table's order.
std::vector<std::string> urdf_joint_type_names() {
  std::vector<std::string> names;
  for (const JointTypeInfo& info : joint_types)
    if (info.type == JointType::free)
      names.push_back("floating");
    else if (urdf_joint_type(info.name))
      names.push_back(info.name);
  return names;
}

/// Joint features urdfdom accepts but kanegen cannot honour, reported here
/// with their element rather than after urdfdom's terse messages.
void check_joint_elements(const UrdfIndex& index, const std::string& file) {
  for (const Element& j : index.joints) {
    const char* type_attribute = j.xml->Attribute("type");
    const std::string type = type_attribute ? type_attribute : "";
    // The types are those of the joint table (model/joint_types.hpp) that URDF has.
    if (!urdf_joint_type(type)) {
      const std::vector<std::string> names = urdf_joint_type_names();
      const std::string guess = nearest(type, names);
      std::string quoted;  // "a", "b" or "c"
      for (std::size_t i = 0; i < names.size(); ++i)
        quoted += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
      const bool json_only = joint_type_named(type) != nullptr;
      throw ModelError(
          file, j.place, type.empty() ? "joint has no type" : "unknown URDF joint type '" + type + "'",
          (json_only ? "a " + type + " joint is for kanegen model files (docs/model-format.md), in a URDF "
           : guess.empty() ? std::string()
                           : "did you mean '" + guess + "'? ") +
              "use type=" + quoted);
    }
    if (j.xml->FirstChildElement("mimic"))
      throw ModelError(file, j.place + "/mimic", "mimic joints are not supported",
                       "remove <mimic> (the joint then gets its own coordinate)");
  }
}

/// The link a joint's <parent> or <child> names, or "" if absent (urdfdom reports that).
std::string joint_link(const Element& joint, const char* tag) {
  const tinyxml2::XMLElement* e = joint.xml->FirstChildElement(tag);
  const char* link = e ? e->Attribute("link") : nullptr;
  return link ? link : "";
}

/// The joints must form a tree. Checked here because urdfdom, given a link
/// that is its own parent, a link with two parent joints or a cycle, fails
/// with a terse message and leaks the links it had connected.
void check_joint_tree(const UrdfIndex& index, const std::string& file) {
  std::map<std::string, const Element*> parent_joint;  // link -> the joint whose child it is
  std::map<std::string, std::string> parent_link;      // link -> its parent link
  for (const Element& j : index.joints) {
    const std::string parent = joint_link(j, "parent"), child = joint_link(j, "child");
    if (parent.empty() || child.empty()) continue;
    if (parent == child)
      throw ModelError(file, j.place + "/child",
                       "joint '" + j.name + "' connects link '" + child + "' to itself",
                       "give it another parent link");
    const auto [other, fresh] = parent_joint.emplace(child, &j);
    if (!fresh)
      throw ModelError(
          file, j.place + "/child",
          "link '" + child + "' is already the child of joint '" + other->second->name + "' (" +
              other->second->place.substr(0, other->second->place.find(':')) + ")",
          "a link hangs from exactly one joint (closed loops are not supported), so remove one of "
          "the joints");
    parent_link[child] = parent;
  }
  // Each link has at most one parent, so following parents either ends at a
  // root or runs into a cycle; each link is walked over once.
  std::map<std::string, int> state;  // 1: on the current walk, 2: done
  for (const auto& entry : parent_link) {
    std::vector<std::string> walk;
    std::string at = entry.first;
    while (parent_link.count(at) && !state.count(at)) {
      state[at] = 1;
      walk.push_back(at);
      at = parent_link.at(at);
    }
    if (state.count(at) && state.at(at) == 1) {  // back on this walk: a cycle through `at`
      std::vector<std::string> cycle(std::find(walk.begin(), walk.end(), at), walk.end());
      cycle.push_back(at);  // each link followed by its parent, back to the first
      throw ModelError(file, parent_joint.at(at)->place + "/parent",
                       "joints form a cycle: " + join(cycle, " -> "),
                       "each chain of parents must end at the root link: make one of these links hang from a "
                       "link outside the cycle");
    }
    for (const std::string& link : walk) state[link] = 2;
  }
}

/// Collects console_bridge output while urdfdom runs instead of printing it.
class CapturedConsole : public console_bridge::OutputHandler {
 public:
  CapturedConsole() { console_bridge::useOutputHandler(this); }
  ~CapturedConsole() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedConsole(const CapturedConsole&) = delete;
  CapturedConsole& operator=(const CapturedConsole&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors.push_back(text);
    else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN)
      warnings.push_back(text);
  }
  std::vector<std::string> errors, warnings;
};

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& text, const UrdfIndex& index,
                                                 const std::string& file) {
  urdf::ModelInterfaceSharedPtr robot;
  std::vector<std::string> errors;
  {
    CapturedConsole console;
    try {
      robot = urdf::parseURDF(text);
    } catch (const std::exception& e) {
      console.errors.push_back(e.what());
    }
    errors = console.errors;
    // urdfdom warns where it guesses (a default it makes up): said, not dropped.
    std::vector<std::string> said;  // urdfdom repeats some (once per pass over the links)
    for (const std::string& warning : console.warnings) {
      if (std::find(said.begin(), said.end(), warning) != said.end()) continue;
      said.push_back(warning);
      std::fprintf(stderr, "warning: %s: urdfdom: %s\n", file.c_str(), warning.c_str());
    }
  }
  if (robot) return robot;
  // urdfdom names the culprit in brackets ("Joint [j3] ..."), often in a
  // follow-up line after the specific one: point at the first one named.
  std::string message = errors.empty() ? "unknown error" : errors.front();
  std::string place = index.robot_place;
  bool placed = false;
  for (const std::string& error : errors) {
    for (const auto* list : {&index.joints, &index.links})
      for (const Element& e : *list)
        if (!placed && error.find("[" + e.name + "]") != std::string::npos) {
          place = e.place;
          placed = true;
          if (error != message) message += " (" + error + ")";
        }
  }
  std::string fix = "fix the URDF as the message says";
  if (message.find("limits") != std::string::npos)
    fix =
        "add <limit lower=\"...\" upper=\"...\" effort=\"...\" velocity=\"...\"/> (URDF requires it for "
        "revolute "
        "and prismatic joints, kanegen ignores them) or use type=\"continuous\"";
  throw ModelError(file, place, "urdfdom cannot read the robot: " + message, fix);
}

Vec3 literal_vec3(double x, double y, double z, const std::string& where) {
  return {Scalar::number(x, where), Scalar::number(y, where), Scalar::number(z, where)};
}

Body read_link(const urdf::Link& link, const Element& e) {
  Body b;
  b.name = link.name;
  b.where = e.place;
  const std::string inertial = e.place + "/inertial";
  // A link without <inertial> is a massless frame (mass and inertia 0).
  b.mass = Scalar::number(link.inertial ? link.inertial->mass : 0.0, inertial + "/mass");
  b.com = literal_vec3(0, 0, 0, inertial + "/origin");
  for (Scalar& s : b.inertia) s = Scalar::number(0.0, inertial + "/inertia");
  if (!link.inertial) return b;
  const urdf::Inertial& in = *link.inertial;
  b.com =
      literal_vec3(in.origin.position.x, in.origin.position.y, in.origin.position.z, inertial + "/origin");
  // URDF gives the inertia in the inertial frame; the Model wants link axes: I_link = R I R^T.
  const urdf::Rotation& q = in.origin.rotation;
  const Eigen::Matrix3d r = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  Eigen::Matrix3d inertia;
  inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  Eigen::Matrix3d rotated = r * inertia * r.transpose();
  // Drop rounding noise of the rotation so exact zeros stay zero in the generated code.
  const double noise = 1e-14 * rotated.cwiseAbs().maxCoeff();
  rotated = rotated.unaryExpr([noise](double v) { return std::abs(v) <= noise ? 0.0 : v; });
  const double entries[6] = {rotated(0, 0), rotated(1, 1), rotated(2, 2),
                             rotated(0, 1), rotated(0, 2), rotated(1, 2)};
  for (int k = 0; k < 6; ++k) b.inertia[k].value = entries[k];
  return b;
}

Joint read_joint(const urdf::Joint& joint, const Element& e, const LoadOptions& options) {
  Joint j;
  j.name = joint.name;
  j.where = e.place;
  // By the attribute's text, through the joint table: check_joint_elements
  // has rejected the names it does not hold.
  j.type = urdf_joint_type(e.xml->Attribute("type"))->type;
  j.parent = joint.parent_link_name;
  j.child = joint.child_link_name;
  const urdf::Pose& origin = joint.parent_to_joint_origin_transform;
  j.origin_xyz =
      literal_vec3(origin.position.x, origin.position.y, origin.position.z, e.place + "/origin/xyz");
  double roll = 0, pitch = 0, yaw = 0;
  origin.rotation.getRPY(roll, pitch, yaw);
  j.origin_rpy = literal_vec3(roll, pitch, yaw, e.place + "/origin/rpy");
  j.axis = {joint.axis.x, joint.axis.y, joint.axis.z};  // urdfdom defaults it to (1, 0, 0)
  j.spring_stiffness = Scalar::number(0.0, e.place + "/dynamics");
  j.spring_rest = Scalar::number(0.0, e.place + "/dynamics");
  const double damping = options.urdf_joint_damping && joint.dynamics ? joint.dynamics->damping : 0.0;
  j.damping = Scalar::number(damping, e.place + "/dynamics");
  j.actuated = j.moves();
  return j;
}

}  // namespace

Model load_urdf_model(const std::string& path, const LoadOptions& options) {
  const std::string text = read_text_file(path);
  UrdfIndex index;
  index_urdf(text, path, index);
  check_vocabulary(index.document.RootElement(), "robot", "<robot>", path);
  check_joint_elements(index, path);
  check_joint_tree(index, path);
  const urdf::ModelInterfaceSharedPtr robot = parse_with_urdfdom(text, index, path);

  Model m;
  m.source_file = path;
  m.name = sanitize_identifier(robot->getName());
  m.ground = robot->getRoot()->name;  // its <inertial>, if any, is ignored: the ground does not move
  const std::string gravity_place = index.robot_place + " (gravity: load option)";
  m.gravity = literal_vec3(0, 0, 0, gravity_place);
  for (int k = 0; k < 3; ++k) m.gravity[k].value = options.urdf_gravity[k];
  // The two XML readers must agree on every name; they differ on malformed
  // entities ("j&1"), where urdfdom would otherwise hand back no element.
  const auto unread = [&](const Element& e) {
    return ModelError(
        path, e.place + "/name", "urdfdom reads this name differently ('" + e.name + "')",
        "write names without '&', '<' and XML entities (letters, digits, '_', '-' and '.' are safe)");
  };
  for (const Element& e : index.links) {
    if (e.name == m.ground) continue;
    const urdf::LinkConstSharedPtr link = robot->getLink(e.name);
    if (!link) throw unread(e);
    m.bodies.push_back(read_link(*link, e));
  }
  for (const Element& e : index.joints) {
    const urdf::JointConstSharedPtr joint = robot->getJoint(e.name);
    if (!joint) throw unread(e);
    m.joints.push_back(read_joint(*joint, e, options));
  }
  expand_compound_joints(m);
  check_model(m, index.robot_place);
  return m;
}

}  // namespace kanegen::model
