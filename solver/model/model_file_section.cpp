#include "solver/model/model_file_section.h"

namespace skewbridge::model::detail {

std::string Join(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) {
      out += ", ";
    }
    out += n;
  }
  return out;
}

std::vector<std::string> AllowedNames(std::string_view allowed) {
  if (const std::size_t paren = allowed.find(" ("); paren != std::string_view::npos) {
    allowed = allowed.substr(0, paren);
  }
  if (allowed.rfind("sections ", 0) == 0) {
    allowed.remove_prefix(9);
  }
  std::vector<std::string> names;
  std::string name;
  for (const char c : std::string(allowed) + ",") {
    if (c == ',') {
      if (!name.empty()) names.push_back(name);
      name.clear();
    } else if (c != ' ' && c != '[' && c != ']' && c != '"') {
      name += c;
    }
  }
  return names;
}

Eigen::Matrix3d Matrix3(Section& s, std::string_view key) {
  const toml::node* node = s.Get(key);
  const std::string problem = "must be a 3 x 3 array of numbers, row by row";
  if (node == nullptr || !node->is_array() || node->as_array()->size() != 3) {
    Fail(s.At(key), s.Field(key), problem);
  }
  Eigen::Matrix3d A;
  const toml::array& rows = *node->as_array();
  for (std::size_t i = 0; i < 3; ++i) {
    if (!rows[i].is_array() || rows[i].as_array()->size() != 3) {
      Fail(s.At(key), s.Field(key), problem);
    }
    const toml::array& row = *rows[i].as_array();
    for (std::size_t j = 0; j < 3; ++j) {
      if (!row[j].is_number()) {
        Fail(s.At(key), s.Field(key), problem);
      }
      A(static_cast<int>(i), static_cast<int>(j)) =
          row[j].is_integer() ? static_cast<double>(*row[j].value<int64_t>())
                              : *row[j].value<double>();
    }
  }
  if (!A.allFinite()) {
    Fail(s.At(key), s.Field(key), "must contain finite numbers only (got NaN or Inf)");
  }
  return A;
}

std::vector<const toml::table*> ArrayOfTables(Section& top, std::string_view name) {
  std::vector<const toml::table*> tables;
  const toml::node* node = top.Get(name);
  if (node == nullptr) {
    return tables;
  }
  const toml::array* array = node->as_array();
  if (array == nullptr) {
    Fail(top.At(name), top.Field(name), "must be an array of tables [[" + std::string(name) + "]]");
  }
  for (const toml::node& entry : *array) {
    if (!entry.is_table()) {
      Fail(Where{top.source(), LineOf(entry)}, top.Field(name),
           "must be an array of tables [[" + std::string(name) + "]]");
    }
    tables.push_back(entry.as_table());
  }
  return tables;
}

std::string Indexed(std::string_view name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

}  // namespace skewbridge::model::detail
