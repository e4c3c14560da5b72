// SPDX-License-Identifier: GPL-2.0-or-later
#include "fem/inp_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>

#include "model/model_error.hpp"

namespace kanegen::fem {

namespace {

using model::ModelError;

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// Comma-separated fields, trimmed; empty fields (a trailing comma) dropped.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= line.size()) {
    const auto comma = line.find(',', start);
    const std::string f =
        trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (!f.empty()) out.push_back(f);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

constexpr long kMaxGenerated = 10000000;

/// Two- and three-node truss elements: Gmsh's elements of a physical curve.
bool is_gmsh_line_type(const std::string& type) { return type == "T3D2" || type == "T3D3"; }
/// Triangles, which Gmsh writes for a physical surface of a tetrahedron or
/// wedge mesh (a boundary node set); kanegen has no triangle family.
bool is_gmsh_triangle_type(const std::string& type) { return type == "CPS3" || type == "CPS6"; }

class Reader {
 public:
  Reader(std::string file) { mesh_.file = std::move(file); }

  InpMesh read(std::istream& in) {
    std::string raw;
    while (std::getline(in, raw)) {
      ++line_;
      const std::string text = trim(raw);
      if (text.empty() || text.rfind("**", 0) == 0) continue;
      if (text[0] == '*') {
        keyword(text);
      } else {
        data(text);
      }
    }
    finish_element();
    check();
    return std::move(mesh_);
  }

 private:
  enum class Block { kNone, kNode, kElement, kLineElements, kNset, kElset, kSkip };

  [[noreturn]] void fail(int line, const std::string& problem, const std::string& fix) const {
    throw ModelError(mesh_.file, "line " + std::to_string(line), problem, fix);
  }

  int integer(const std::string& text, const std::string& what) const {
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || errno == ERANGE || v <= 0 || v > 2147483647L)
      fail(line_, "'" + text + "' is not " + what, "write a positive integer");
    return static_cast<int>(v);
  }

  double real(const std::string& text) const {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      fail(line_, "'" + text + "' is not a coordinate", "write a finite number");
    return v;
  }

  /// KEY=VALUE parameters of a keyword line, keys upper-case; a bare KEY maps to "".
  std::map<std::string, std::string> parameters(const std::vector<std::string>& f) const {
    std::map<std::string, std::string> out;
    for (std::size_t i = 1; i < f.size(); ++i) {
      const auto eq = f[i].find('=');
      out[upper(trim(f[i].substr(0, eq)))] = eq == std::string::npos ? "" : trim(f[i].substr(eq + 1));
    }
    return out;
  }

  std::string set_name(const std::map<std::string, std::string>& params, const std::string& key,
                       const std::string& keyword) const {
    const auto it = params.find(key);
    if (it == params.end() || it->second.empty())
      fail(line_, keyword + " without " + key + "=", "name the set: " + keyword + ", " + key + "=NAME");
    return upper(it->second);
  }

  void keyword(const std::string& text) {
    finish_element();
    const std::vector<std::string> f = fields(text);
    const std::string word = upper(f.empty() ? text : f[0]);
    const auto params = parameters(f);
    generate_ = params.count("GENERATE") > 0;
    set_ = "";
    if (word == "*NODE") {
      block_ = Block::kNode;
      if (params.count("NSET")) set_ = set_name(params, "NSET", "*NODE");
    } else if (word == "*ELEMENT") {
      block_ = Block::kElement;
      const auto type = params.find("TYPE");
      if (type == params.end())
        fail(line_,
             "*ELEMENT without TYPE=", std::string("give the element type, one of ") + supported_ccx_names());
      if (is_gmsh_line_type(upper(type->second)) || is_gmsh_triangle_type(upper(type->second))) {
        // The line (or triangle) elements Gmsh writes for a physical curve
        // (surface) of a 2D (3D) mesh's boundary node set: only their node set matters.
        if (is_gmsh_triangle_type(upper(type->second))) skipped_triangles_ = true;
        block_ = Block::kLineElements;
        return;
      }
      if (!family_from_ccx_name(upper(type->second), family_))
        fail(line_, "unknown element type '" + type->second + "'",
             std::string("kanegen reads ") + supported_ccx_names() +
                 " (mesh with these, e.g. Gmsh: Recombine and Mesh.SecondOrderIncomplete = 1)");
      if (params.count("ELSET")) set_ = set_name(params, "ELSET", "*ELEMENT");
    } else if (word == "*NSET") {
      block_ = Block::kNset;
      set_ = set_name(params, "NSET", "*NSET");
      mesh_.node_sets[set_];  // an empty set still exists
    } else if (word == "*ELSET") {
      block_ = Block::kElset;
      set_ = set_name(params, "ELSET", "*ELSET");
      mesh_.element_sets[set_];
    } else if (word == "*INCLUDE") {
      fail(line_, "*INCLUDE is not supported", "paste the included file's contents in its place");
    } else {
      block_ = Block::kSkip;  // material, steps, heading...: the kanegen model gives these
    }
  }

  void data(const std::string& text) {
    const std::vector<std::string> f = fields(text);
    switch (block_) {
      case Block::kNone:
        fail(line_, "data line before any keyword", "start the file with *NODE");
      case Block::kLineElements:
        if (!f.empty()) line_element_ids_.insert(std::atoi(f[0].c_str()));
        return;
      case Block::kSkip:
        return;
      case Block::kNode:
        return node(f);
      case Block::kElement:
        return element_data(f);
      case Block::kNset:
      case Block::kElset:
        return set_members(f);
    }
  }

  void node(const std::vector<std::string>& f) {
    if (f.size() < 3 || f.size() > 4)
      fail(line_, "a *NODE line needs an id and 2 or 3 coordinates", "write: id, x, y[, z]");
    MeshNode n;
    n.id = integer(f[0], "a node id");
    n.line = line_;
    for (std::size_t k = 1; k < f.size(); ++k) n.position[static_cast<int>(k) - 1] = real(f[k]);
    const auto [it, inserted] = mesh_.node_index_of_id.emplace(n.id, static_cast<int>(mesh_.nodes.size()));
    if (!inserted)
      fail(line_,
           "node " + f[0] + " is defined twice (first on line " +
               std::to_string(mesh_.nodes[it->second].line) + ")",
           "give every node its own id");
    mesh_.nodes.push_back(n);
    if (!set_.empty()) mesh_.node_sets[set_].push_back(n.id);
  }

  /// Element records may continue over several lines: ids are collected until the type's node count.
  void element_data(const std::vector<std::string>& f) {
    for (const std::string& field : f) {
      if (!pending_) {
        pending_ = true;
        current_ = MeshElement{};
        current_.id = integer(field, "an element id");
        current_.family = family_;
        current_.line = line_;
        continue;
      }
      if (static_cast<int>(current_.nodes.size()) == family_num_nodes(family_))
        fail(line_,
             "element " + std::to_string(current_.id) + " has more than " +
                 std::to_string(family_num_nodes(family_)) + " nodes",
             std::string("a ") + ccx_type_name(family_) + " element lists " +
                 std::to_string(family_num_nodes(family_)) + " nodes after its id");
      current_.nodes.push_back(integer(field, "a node id"));
    }
    if (pending_ && static_cast<int>(current_.nodes.size()) == family_num_nodes(family_)) finish_element();
  }

  void finish_element() {
    if (!pending_) return;
    pending_ = false;
    const int expected = family_num_nodes(current_.family);
    if (static_cast<int>(current_.nodes.size()) != expected)
      fail(current_.line,
           "element " + std::to_string(current_.id) + " has " + std::to_string(current_.nodes.size()) +
               " nodes, a " + ccx_type_name(current_.family) + " has " + std::to_string(expected),
           "list all its nodes (a record may continue on the next line)");
    if (!element_ids_.emplace(current_.id, current_.line).second)
      fail(current_.line,
           "element " + std::to_string(current_.id) + " is defined twice (first on line " +
               std::to_string(element_ids_[current_.id]) + ")",
           "give every element its own id");
    if (!set_.empty()) mesh_.element_sets[set_].push_back(current_.id);
    mesh_.elements.push_back(std::move(current_));
  }

  void set_members(const std::vector<std::string>& f) {
    auto& sets = block_ == Block::kNset ? mesh_.node_sets : mesh_.element_sets;
    std::vector<int>& members = sets[set_];
    if (generate_) {
      if (f.size() < 2 || f.size() > 3)
        fail(line_, "a GENERATE line needs first, last[, increment]", "write: first, last, increment");
      const int first = integer(f[0], "a first id"), last = integer(f[1], "a last id");
      const int step = f.size() == 3 ? integer(f[2], "an increment") : 1;
      if (last < first) fail(line_, "GENERATE's last id is below its first", "write: first, last, increment");
      // A typo in an id must not make a set of a billion members.
      if ((static_cast<long>(last) - first) / step >= kMaxGenerated)
        fail(line_, "GENERATE would list more than " + std::to_string(kMaxGenerated) + " ids",
             "check first, last and increment");
      for (long id = first; id <= last; id += step) members.push_back(static_cast<int>(id));
      return;
    }
    for (const std::string& field : f) {
      if (std::isdigit(static_cast<unsigned char>(field[0]))) {
        members.push_back(integer(field, "an id"));
        continue;
      }
      const auto other = sets.find(upper(field));  // a set may list sets defined before it
      if (other == sets.end() || upper(field) == set_)
        fail(line_, "set '" + field + "' is not defined before this line",
             "define it earlier, or list ids (integers) here");
      members.insert(members.end(), other->second.begin(), other->second.end());
    }
    set_lines_[&members] = line_;
  }

  void check() {
    if (mesh_.elements.empty() && skipped_triangles_)
      fail(line_,
           "the file's only elements are triangles (CPS3/CPS6), which kanegen reads only as faces of a solid",
           std::string("mesh a plane body with quadrilaterals (Gmsh: Recombine), or a solid with ") +
               supported_ccx_names());
    if (mesh_.elements.empty())
      fail(line_, "the file has no elements",
           std::string("add an *ELEMENT block of type ") + supported_ccx_names());
    for (const MeshElement& e : mesh_.elements)
      for (int id : e.nodes)
        if (!mesh_.node_index_of_id.count(id))
          fail(e.line,
               "element " + std::to_string(e.id) + " refers to node " + std::to_string(id) +
                   ", which the file does not define",
               "add the node to a *NODE block or correct the element");
    for (auto& [name, ids] : mesh_.node_sets) {
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      for (int id : ids)
        if (!mesh_.node_index_of_id.count(id))
          fail(set_lines_.count(&ids) ? set_lines_[&ids] : line_,
               "node set " + name + " lists node " + std::to_string(id) + ", which the file does not define",
               "remove it from the set or define the node");
    }
    for (auto& [name, ids] : mesh_.element_sets) {
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      // Line elements are not kept: nor are they in the sets.
      ids.erase(
          std::remove_if(ids.begin(), ids.end(), [&](int id) { return line_element_ids_.count(id) > 0; }),
          ids.end());
      for (int id : ids)
        if (!element_ids_.count(id))
          fail(set_lines_.count(&ids) ? set_lines_[&ids] : line_,
               "element set " + name + " lists element " + std::to_string(id) +
                   ", which the file does not define",
               "remove it from the set or define the element");
    }
  }

  InpMesh mesh_;
  bool skipped_triangles_ = false;
  int line_ = 0;
  Block block_ = Block::kNone;
  ContinuumFamily family_ = ContinuumFamily::kHex8;
  std::string set_;
  bool generate_ = false;
  bool pending_ = false;
  std::set<int> line_element_ids_;
  MeshElement current_;
  std::map<int, int> element_ids_;                    ///< id -> line
  std::map<const std::vector<int>*, int> set_lines_;  ///< a set's last data line
};

const std::vector<int>& find_set(const InpMesh& mesh, const std::map<std::string, std::vector<int>>& sets,
                                 const std::string& name, const std::string& kind,
                                 const std::string& keyword) {
  const auto it = sets.find(upper(name));
  if (it != sets.end()) return it->second;
  std::string have;
  for (const auto& [n, ids] : sets) have += (have.empty() ? "" : ", ") + n;
  throw ModelError(mesh.file, kind + " set " + name, "the mesh has no " + kind + " set '" + name + "'",
                   "define it with " + keyword + "=" + name + " (the file has " +
                       (have.empty() ? std::string("none") : have) + ")");
}

}  // namespace

int InpMesh::node_index(int id) const {
  const auto it = node_index_of_id.find(id);
  return it == node_index_of_id.end() ? -1 : it->second;
}

const std::vector<int>& InpMesh::node_set(const std::string& name) const {
  return find_set(*this, node_sets, name, "node", "*NSET, NSET");
}

const std::vector<int>& InpMesh::element_set(const std::string& name) const {
  return find_set(*this, element_sets, name, "element", "*ELSET, ELSET");
}

InpMesh read_inp_mesh(std::istream& in, const std::string& file) { return Reader(file).read(in); }

InpMesh read_inp_mesh_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ModelError(path, "", "cannot open the mesh file", "check the path");
  return read_inp_mesh(in, path);
}

}  // namespace kanegen::fem
