#pragma once
/// @file
/// Reading the TOML tables of a model file (docs/model-format.md), private to solver/model:
/// `Section` remembers the keys read from one table so that any other key is reported with its
/// key path and line, the allowed keys and the nearest of them. The readers of each table
/// (model_file_tables.h) are written with it.

#include <toml++/toml.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "solver/common/nearest.h"
#include "solver/model/checks.h"

namespace skewbridge::model::detail {

/// Degrees to radians.
inline constexpr double kDegToRad = std::numbers::pi / 180.0;

/// The line of a TOML node in its file (0 when it has none).
inline long LineOf(const toml::node& node) { return static_cast<long>(node.source().begin.line); }

/// The names joined by ", ".
std::string Join(std::initializer_list<std::string_view> names);

/// The key names of an "allowed" text such as `kind, w0, W0 (with kind = "uncoupled")` or
/// `sections [[deck]], excitation`: the words between commas, without brackets and quotes.
std::vector<std::string> AllowedNames(std::string_view allowed);

/// One TOML table being read: remembers which keys were used so that any other key is reported
/// as unknown, with the key path and line, the allowed keys and the nearest of them.
class Section {
 public:
  Section(const toml::table& table, std::string path, std::string_view source)
      : table_(table), path_(std::move(path)), source_(source) {}

  // The TOML key path; keys that are not bare TOML keys ("+x") are quoted.
  std::string Field(std::string_view key) const {
    bool bare = !key.empty();
    for (char c : key) {
      bare = bare && (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_');
    }
    std::string path = path_;
    if (!path.empty()) {
      path += '.';
    }
    if (!bare) {
      path += '"';
    }
    path += key;
    if (!bare) {
      path += '"';
    }
    return path;
  }
  Where At(std::string_view key) const {
    const toml::node* node = table_.get(key);
    return Where{source_, node != nullptr ? LineOf(*node) : TableLine()};
  }
  long TableLine() const { return LineOf(table_); }
  bool Has(std::string_view key) const { return table_.contains(key); }
  const toml::node* Get(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  // Declares the keys this table may hold (as Finish will): a required key found missing is
  // then reported as a misspelling when the table holds an unknown key, which it most often
  // is. `elsewhere` names other forms of the table and their keys (`kind = "principal"`,
  // `w1, w2, w_theta`), for a key that is allowed only there.
  void Expect(std::string_view allowed,
              std::vector<std::pair<std::string, std::string>> elsewhere = {}) {
    allowed_ = allowed;
    elsewhere_ = std::move(elsewhere);
  }

  // Fails on a key outside the keys declared by Expect (nothing when none were declared).
  void RejectUndeclared() const {
    if (!allowed_.empty()) {
      const std::vector<std::string> names = AllowedNames(allowed_);
      RejectUnknown([&](std::string_view k) {
        return std::find(names.begin(), names.end(), k) == names.end();
      });
    }
  }

  [[noreturn]] void Missing(std::string_view key, std::string_view what) const {
    RejectUndeclared();
    Fail(Where{source_, TableLine()}, Field(key),
         std::string("missing required key (").append(what).append(")"));
  }

  std::optional<double> Number(std::string_view key) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return std::nullopt;
    }
    if (!node->is_number()) {
      Fail(At(key), Field(key), "must be a number");
    }
    const double value =
        node->is_integer() ? static_cast<double>(*node->value<int64_t>()) : *node->value<double>();
    CheckFinite(value, Field(key), At(key));
    return value;
  }

  double RequiredNumber(std::string_view key, std::string_view what) {
    const std::optional<double> value = Number(key);
    if (!value) {
      Missing(key, what);
    }
    return *value;
  }

  std::optional<std::string> String(std::string_view key,
                                    std::initializer_list<std::string_view> allowed) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return std::nullopt;
    }
    const std::string allowed_text = Join(allowed);
    if (!node->is_string()) {
      Fail(At(key), Field(key), "must be a string (allowed: " + allowed_text + ")");
    }
    std::string value = *node->value<std::string>();
    if (allowed.size() > 0) {
      bool ok = false;
      for (std::string_view a : allowed) {
        ok = ok || value == a;
      }
      if (!ok) {
        Fail(At(key), Field(key), "must be one of " + allowed_text + " (got \"" + value + "\")");
      }
    }
    return value;
  }

  // A sub-table, or nullopt.
  const toml::table* Table(std::string_view key) {
    const toml::node* node = Get(key);
    if (node == nullptr) {
      return nullptr;
    }
    if (!node->is_table()) {
      Fail(At(key), Field(key), "must be a table");
    }
    return node->as_table();
  }

  // Every key not read is unknown.
  void Finish(std::string_view allowed) {
    allowed_ = allowed;
    RejectUnknown([&](std::string_view k) { return used_.count(std::string(k)) == 0; });
  }

  // A key read only to be rejected in this context.
  void Reject(std::string_view key, std::string_view why) {
    if (Has(key)) {
      Fail(At(key), Field(key), why);
    }
  }

  std::string_view source() const { return source_; }
  /// The table's own key path ("abutments.backfill").
  const std::string& path() const { return path_; }

 private:
  // Fails on the first key (by line) for which `unknown` holds, naming the allowed keys, the
  // nearest of them, or the form of the table that takes the key.
  template <class Predicate>
  void RejectUnknown(Predicate unknown) const {
    const toml::node* first = nullptr;
    std::string first_key;
    for (auto&& [key, node] : table_) {
      if (unknown(key.str()) && (first == nullptr || LineOf(node) < LineOf(*first))) {
        first = &node;
        first_key = key.str();
      }
    }
    if (first == nullptr) {
      return;
    }
    const bool sections = allowed_.rfind("sections ", 0) == 0;  // the file's top level
    std::string problem = sections ? "unknown section (allowed: " + allowed_.substr(9) + ")"
                                   : "unknown key (allowed: " + allowed_ + ")";
    for (const auto& [form, keys] : elsewhere_) {
      const std::vector<std::string> names = AllowedNames(keys);
      if (std::find(names.begin(), names.end(), first_key) != names.end()) {
        Fail(Where{source_, LineOf(*first)}, Field(first_key),
             problem + "; it is a key of " + form);
      }
    }
    Fail(Where{source_, LineOf(*first)}, Field(first_key),
         problem + DidYouMean(first_key, AllowedNames(allowed_)));
  }

  const toml::table& table_;
  std::string path_;
  std::string_view source_;
  std::set<std::string> used_;
  std::string allowed_;  // the allowed keys as Finish names them, once known
  std::vector<std::pair<std::string, std::string>> elsewhere_;
};

/// The 3 x 3 matrix `key`, given row by row, finite.
Eigen::Matrix3d Matrix3(Section& s, std::string_view key);

/// The tables of a TOML array of tables ([[name]]), each with its line.
std::vector<const toml::table*> ArrayOfTables(Section& top, std::string_view name);

/// "name[i]": the key path of the i-th table of the array of tables `name`.
std::string Indexed(std::string_view name, std::size_t i);

/// Declares the keys of `kind` among `forms` (kind, keys), the other kinds as where a key
/// foreign to this one belongs.
template <std::size_t N>
void ExpectForm(Section& s, std::string_view kind,
                const std::array<std::pair<std::string_view, std::string_view>, N>& forms) {
  std::string_view keys;
  std::vector<std::pair<std::string, std::string>> elsewhere;
  for (const auto& [k, text] : forms) {
    if (k == kind) {
      keys = text;
    } else {
      elsewhere.emplace_back("kind = \"" + std::string(k) + "\"", std::string(text));
    }
  }
  s.Expect(keys, std::move(elsewhere));
}

}  // namespace skewbridge::model::detail
