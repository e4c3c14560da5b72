// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/result_table.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "kanegen/runtime/text.hpp"

namespace kanegen::animate {
namespace {

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream stream(line);
  for (std::string cell; std::getline(stream, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace

int ResultTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == name) return static_cast<int>(k);
  return -1;
}

ResultTable read_result_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read; give a CSV written by kanegen simulate");
  ResultTable table;
  table.file = path;
  std::string line;
  if (!std::getline(in, line) || (table.columns = cells_of(line)).empty() || table.columns[0] != "t")
    throw std::runtime_error(
        path + ": line 1: not a header starting with t; give a CSV written by kanegen simulate");
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = cells_of(line);
    const std::string at = path + ": line " + std::to_string(number) + ": ";
    if (cells.size() != table.columns.size())
      throw std::runtime_error(at + std::to_string(cells.size()) + " cells under a header of " +
                               std::to_string(table.columns.size()) +
                               "; give the CSV as kanegen simulate wrote it (was it cut short?)");
    std::vector<double> row(cells.size());
    for (std::size_t k = 0; k < cells.size(); ++k)
      if (!runtime::parse_number(cells[k], &row[k]))
        throw std::runtime_error(at + "column '" + table.columns[k] + "' holds '" + cells[k] +
                                 "', not a finite number; give the CSV as kanegen simulate wrote it");
    table.rows.push_back(std::move(row));
  }
  if (table.rows.empty())
    throw std::runtime_error(path + ": has no rows (the run wrote only the header); simulate for longer");
  return table;
}

std::vector<std::size_t> chosen_rows(std::size_t row_count, std::size_t frames) {
  std::vector<std::size_t> rows;
  if (row_count <= frames || frames < 2) {
    for (std::size_t r = 0; r < row_count; ++r) rows.push_back(r);
    return rows;
  }
  for (std::size_t k = 0; k < frames; ++k)
    rows.push_back((k * (row_count - 1) + (frames - 1) / 2) / (frames - 1));
  return rows;
}

}  // namespace kanegen::animate
