#include "jobs/app/parse_error.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "solver/common/nearest.h"

namespace skewbridge::app {
namespace {

// The deepest sub-command the command line reached (the program itself when none).
CLI::App* Deepest(CLI::App* app) {
  const std::vector<CLI::App*> parsed = app->get_subcommands();  // those on the command line
  return parsed.empty() ? app : Deepest(parsed.front());
}

// "records info": the sub-command's path as typed, without the program's name ("" for the
// program itself).
std::string CommandPath(CLI::App* app) {
  std::string path;
  for (CLI::App* p = app; p->get_parent() != nullptr; p = p->get_parent()) {
    path = p->get_name() + (path.empty() ? "" : " " + path);
  }
  return path;
}

// "records info: " (or nothing for the program itself), to start a message with.
std::string Prefix(CLI::App* app) {
  const std::string path = CommandPath(app);
  return path.empty() ? path : path + ": ";
}

// "(see skewbridge records info --help)"
std::string SeeHelp(CLI::App* app) {
  const std::string path = CommandPath(app);
  return "(see skewbridge " + (path.empty() ? "" : path + " ") + "--help)";
}

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) {
    out += (out.empty() ? "" : ", ") + n;
  }
  return out;
}

std::vector<std::string> SubcommandNames(CLI::App* app) {
  std::vector<std::string> names;
  for (CLI::App* sub : app->get_subcommands({})) {
    names.push_back(sub->get_name());
  }
  return names;
}

// Every option name of `app` (--out, -h, ...), in the order declared.
std::vector<std::string> OptionNames(CLI::App* app) {
  std::vector<std::string> names;
  for (CLI::Option* opt : app->get_options({})) {
    for (const std::string& l : opt->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

// What the value of an option must be, from CLI11's type name.
std::string Expected(CLI::Option* opt) {
  const std::string type = opt != nullptr ? opt->get_type_name() : "";
  if (type == "FLOAT") return "a number";
  if (type == "INT") return "a whole number";
  if (type == "UINT") return "a whole number >= 0";
  if (type.empty()) return "a value";
  return "a value of type " + type;
}

CLI::Option* FindOption(CLI::App* app, const std::string& name) {
  for (CLI::Option* opt : app->get_options({})) {
    if (opt->check_name(name)) {
      return opt;
    }
  }
  return nullptr;
}

// The one-line form of a text that may hold line breaks.
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

std::string Unexpected(CLI::App* cmd, const std::vector<std::string>& extras) {
  const std::string path = Prefix(cmd);
  const std::string& word = extras.front();
  if (!word.empty() && word[0] == '-') {
    std::string name = word.substr(0, word.find('='));
    const std::vector<std::string> options = OptionNames(cmd);
    return path + "unknown option " + name + "; allowed: " + Join(options) +
           DidYouMean(name, options);
  }
  const std::vector<std::string> subs = SubcommandNames(cmd);
  if (!subs.empty() && cmd->get_subcommands().empty()) {
    return path + "unknown sub-command '" + word + "'; allowed: " + Join(subs) +
           DidYouMean(word, subs);
  }
  return path + "unexpected argument '" + word + "' " + SeeHelp(cmd);
}

}  // namespace

std::string DescribeParseError(CLI::App& app, const CLI::ParseError& e) {
  CLI::App* cmd = Deepest(&app);
  const std::string path = Prefix(cmd);
  const std::string message = e.what();
  const std::vector<std::string> extras = cmd->remaining();
  if (!extras.empty()) {
    return Unexpected(cmd, extras);
  }
  const std::string kind = e.get_name();
  if (kind == "RequiredError") {
    const std::vector<std::string> subs = SubcommandNames(cmd);
    if (!subs.empty() && cmd->get_subcommands().empty() &&
        message.find("ubcommand") != std::string::npos) {
      return path + "a sub-command is required; allowed: " + Join(subs);
    }
    const std::string suffix = " is required";
    if (message.size() > suffix.size() &&
        message.compare(message.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string name = message.substr(0, message.size() - suffix.size());
      CLI::Option* opt = FindOption(cmd, name);
      const std::string what = opt != nullptr ? " (" + opt->get_description() + ")" : "";
      return path + name + " is required" + what;
    }
  }
  if (kind == "ConversionError") {
    // "Could not convert: --dt = abc"
    const std::string head = "Could not convert: ";
    const std::size_t eq = message.find(" = ");
    if (message.rfind(head, 0) == 0 && eq != std::string::npos) {
      const std::string name = message.substr(head.size(), eq - head.size());
      const std::string value = message.substr(eq + 3);
      return path + name + ": '" + value + "' is not " + Expected(FindOption(cmd, name));
    }
  }
  if (kind == "ArgumentMismatch") {
    // "--dt: 1 required FLOAT missing"
    const std::size_t colon = message.find(": ");
    if (colon != std::string::npos && message.find("missing") != std::string::npos) {
      const std::string name = message.substr(0, colon);
      return path + name + " needs " + Expected(FindOption(cmd, name));
    }
  }
  if (kind == "ValidationError") {
    // "--max-cells: Value -5 not in range 2.2e-308 to 1.8e308"
    const std::size_t colon = message.find(": Value ");
    const std::size_t range = message.find(" not in range ");
    if (colon != std::string::npos && range != std::string::npos && range > colon) {
      const std::string name = message.substr(0, colon);
      const std::string value = message.substr(colon + 8, range - colon - 8);
      // CLI::PositiveNumber, the only range the program declares, is [smallest normal double,
      // largest double]: its lower bound prints as 0.000000.
      const std::size_t to = message.find(" to ", range);
      const std::string low =
          message.substr(range + 14, to == std::string::npos ? std::string::npos : to - range - 14);
      const bool positive = std::strtod(low.c_str(), nullptr) == 0.0;
      char* end = nullptr;
      std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0') {
        return path + name + ": '" + value + "' is not a number";
      }
      return path + name + ": '" + value + "' is not allowed; " +
             (positive ? "must be > 0" : OneLine(message.substr(colon + 2)));
    }
    return path + OneLine(message);
  }
  return path + OneLine(message) + " " + SeeHelp(cmd);
}

}  // namespace skewbridge::app
