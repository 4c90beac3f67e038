// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/measurement.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/errors.hpp"
#include "core/text_file.hpp"

namespace imcol::calib {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else out.back() += c;
  }
  for (auto& c : out) c = trim(c);
  return out;
}

double number(const std::string& cell, const std::string& where, const std::string& column) {
  if (cell.empty()) throw InputError(where, column, "empty cell");
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (end != cell.c_str() + cell.size()) throw InputError(where, column, "not a number: '" + cell + "'");
  if (!std::isfinite(v)) throw InputError(where, column, "not a finite number: '" + cell + "'");
  // The scene reader's range for any number: beyond it a residual's square, or its sum, would overflow.
  if (std::abs(v) > 1e30 || (v != 0 && std::abs(v) < 1e-30))
    throw InputError(where, column, "out of range: " + cell + " (a measured value is 0 or of magnitude in [1e-30, 1e30])");
  return v;
}

/// A scene key as --set takes it: letters, digits, '_', '-', '.', '[', ']'.
bool key_like(const std::string& k) {
  return !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '[' || c == ']';
  });
}

/// The measurement CSV read line by line: the header decides the kind, each data row joins it.
struct MeasurementParser {
  explicit MeasurementParser(const std::string& file) : path(file) {}
  const std::string& path;
  std::vector<std::string> header;
  int header_line = 0;
  bool trajectory = false;
  MeasuredTrajectory tr;
  MeasuredTable tb;
  std::size_t e_col = 0;

  /// Every column named, none twice.
  void check_names(const std::string& where) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i].empty()) throw InputError(where, "", "column " + std::to_string(i + 1) + " has no name");
      if (std::find(header.begin(), header.begin() + static_cast<long>(i), header[i]) != header.begin() + static_cast<long>(i))
        throw InputError(where, header[i], "column given twice");
    }
  }

  /// t, then z1 and/or z2.
  void trajectory_header(const std::string& where, int lineno) {
    for (std::size_t i = 1; i < header.size(); ++i)
      if (header[i] != "z1" && header[i] != "z2")
        throw InputError(where, header[i], "unknown column of a trajectory (expected t, then z1 and/or z2, in m)");
    if (header.size() < 2) throw InputError(where, "", "a trajectory needs a column z1 or z2 after t");
    tr.path = path;
    tr.header_line = lineno;
    tr.columns.assign(header.begin() + 1, header.end());
    tr.z.resize(tr.columns.size());
  }

  /// Scene keys and e (in column e_col).
  void table_header(const std::string& where) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (i != e_col && !key_like(header[i]))
        throw InputError(where, header[i], "unknown column of an e table (expected scene keys as --set takes them, and e)");
    if (header.size() < 2) throw InputError(where, "", "an e table needs at least one scene key beside e");
    tb.path = path;
    for (std::size_t i = 0; i < header.size(); ++i)
      if (i != e_col) tb.keys.push_back(header[i]);
  }

  void read_header(const std::string& row, const std::string& where, int lineno) {
    header = cells(row);
    header_line = lineno;
    check_names(where);
    trajectory = header[0] == "t";
    const auto e_it = std::find(header.begin(), header.end(), "e");
    if (trajectory) {
      trajectory_header(where, lineno);
    } else if (e_it != header.end()) {
      e_col = static_cast<std::size_t>(e_it - header.begin());
      table_header(where);
    } else {
      throw InputError(where, header[0], "unknown kind of measurement: a trajectory starts with a column t, an e table has a column e");
    }
  }

  void trajectory_row(const std::vector<std::string>& c, const std::string& where, int lineno) {
    const double t = number(c[0], where, "t");
    if (!tr.t.empty() && !(t > tr.t.back()))
      throw InputError(where, "t", "times must increase strictly: " + fmt_number(t) + " s after " + fmt_number(tr.t.back()) +
                                       " s (line " + std::to_string(tr.lines.back()) + ")");
    tr.t.push_back(t);
    for (std::size_t k = 1; k < c.size(); ++k) tr.z[k - 1].push_back(number(c[k], where, header[k]));
    tr.lines.push_back(lineno);
  }

  void table_row(const std::vector<std::string>& c, const std::string& where, int lineno) {
    std::vector<double> row;
    for (std::size_t k = 0; k < c.size(); ++k)
      if (k != e_col) row.push_back(number(c[k], where, header[k]));
    const double e = number(c[e_col], where, "e");
    if (e < 0 || e > 1) throw InputError(where, "e", "outside [0, 1]: " + fmt_number(e));
    tb.values.push_back(std::move(row));
    tb.e.push_back(e);
    tb.lines.push_back(lineno);
  }

  void data_row(const std::string& row, const std::string& where, int lineno) {
    const auto c = cells(row);
    if (c.size() != header.size())
      throw InputError(where, "", std::to_string(c.size()) + " cells, the header (line " + std::to_string(header_line) + ") has " +
                                      std::to_string(header.size()));
    if (trajectory) trajectory_row(c, where, lineno);
    else table_row(c, where, lineno);
  }

  /// The measurement read, with enough rows.
  Measurement finish() const {
    if (header.empty()) throw InputError(path, "", "no header line (a trajectory: t,z1[,z2]; an e table: scene keys and e)");
    if (trajectory) {
      if (tr.t.size() < kMinTrajectoryRows)
        throw InputError(path, "", std::to_string(tr.t.size()) + " rows: a trajectory needs at least " + std::to_string(kMinTrajectoryRows));
      return tr;
    }
    if (tb.e.size() < kMinTableRows)
      throw InputError(path, "", std::to_string(tb.e.size()) + " rows: an e table needs at least " + std::to_string(kMinTableRows));
    return tb;
  }
};

}  // namespace

Measurement read_measurement(const std::string& path) {
  return parse_measurement(path, read_text_file(path, "measurement", kMaxMeasurementBytes, "CSV"));
}

Measurement parse_measurement(const std::string& path, const std::string& text) {
  // A UTF-8 byte order mark (spreadsheets write one) is not part of the first column's name.
  constexpr char kBom[] = "\xEF\xBB\xBF";
  std::istringstream in(text.rfind(kBom, 0) == 0 ? text.substr(3) : text);
  MeasurementParser parser(path);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string row = trim(line);
    if (row.empty() || row[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(lineno);
    if (parser.header.empty()) parser.read_header(row, where, lineno);
    else parser.data_row(row, where, lineno);
  }
  return parser.finish();
}

}  // namespace imcol::calib
