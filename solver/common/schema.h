#pragma once
/// @file
/// One description per stored struct, in the manner of Drake's `Serialize(Archive*)` with
/// name-value pairs (drake/common/name_value.h): a struct that run files and cubes store (a
/// policy of thresholds, a table of constants) lists its members once, in a member function
///
///     template <typename Archive>
///     void Describe(Archive* a) {
///       a->Visit(SB_NVP(velocity_tolerance), {"1", "v_ref", schema::Interval::Open(0, 1)});
///       a->Visit(SB_NVP(finite_check_steps), {"1", "", schema::Interval::PowerOfTwo()});
///       a->Visit(SB_NVP(jam));        // a rule: stored 1 (on) or 0 (off)
///       a->Visit(SB_NVP(contact));    // a described struct: its names get the prefix "contact."
///     }
///
/// and every use of the struct as data comes from that one list: the stored entries (Entries:
/// name, value, unit, the scale it multiplies, what is allowed), the validation (Validate: one
/// InputError naming the member, what is allowed and the value given), the documentation table
/// (MarkdownRows) and reading stored entries back into a struct (Assign). A member left out of
/// Describe is in none of them; two lists kept in step by hand cannot drift apart.
///
/// Members are visited through pointers, so Describe is not const; the const uses below visit a
/// copy (the structs described are small aggregates of numbers).

#include <concepts>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace skewbridge::schema {

/// The values a stored number may take: a finite value within [lower, upper] (an open end
/// excludes its bound), or a power of two (1, 2, 4, ...).
struct Interval {
  double lower = -std::numeric_limits<double>::infinity();  ///< the lowest value allowed
  double upper = std::numeric_limits<double>::infinity();   ///< the highest value allowed
  bool lower_open = false;                                  ///< lower itself is not allowed
  bool upper_open = false;                                  ///< upper itself is not allowed
  bool power_of_two = false;  ///< only 1, 2, 4, ... (an integral member)

  /// Any finite value.
  static Interval Finite() { return {}; }
  /// x >= lower.
  static Interval AtLeast(double lower) { return {lower}; }
  /// x > lower.
  static Interval Above(double lower) {
    return {lower, std::numeric_limits<double>::infinity(), true};
  }
  /// lower <= x <= upper.
  static Interval Closed(double lower, double upper) { return {lower, upper}; }
  /// lower < x < upper.
  static Interval Open(double lower, double upper) { return {lower, upper, true, true}; }
  /// lower <= x < upper.
  static Interval ClosedOpen(double lower, double upper) { return {lower, upper, false, true}; }
  /// 1, 2, 4, 8, ...
  static Interval PowerOfTwo() {
    Interval i{1.0};
    i.power_of_two = true;
    return i;
  }

  /// Whether `x` is allowed (NaN and the infinities never are).
  bool Admits(double x) const;
  /// What is allowed, as the documentation and the messages say it: "at least 1", "> 0",
  /// "in [0, 1)", "a power of two (1, 2, 4, ...)", "0 or 1" for a rule.
  std::string Text() const;
};

/// How a member is stored and documented: its unit, the scale it multiplies and what is
/// allowed.
struct Meta {
  const char* unit = "1";         ///< "1", "s", "rad/s", "ulp", ...
  const char* relative_to = "";   ///< the scale the member multiplies ("" for none)
  Interval allowed = Interval{};  ///< the values Validate accepts
};

/// What a member is: a real number, a count (an integer) or a rule (on or off).
enum class Kind { kReal, kCount, kRule };

/// A name and a pointer to a member, as SB_NVP makes them (drake::NameValue's idea).
template <typename T>
struct NameValue {
  const char* name;  ///< the member's name as stored
  T* value;          ///< the member
};

/// One member of a described struct as data: what run files and cubes store (HDF5 attributes:
/// float64 for a real, int64 for a count or a rule) and what the documentation lists.
struct Entry {
  std::string name;         ///< its stored name ("contact.tie_tolerance" for a nested member)
  double value = 0.0;       ///< its value (a rule: 1 on, 0 off)
  Kind kind = Kind::kReal;  ///< real, count or rule
  std::string unit;         ///< "1", "s", "rad/s", "ulp", ...
  std::string relative_to;  ///< the scale it multiplies ("" for none)
  Interval allowed;         ///< what Validate accepts

  /// Stored as an integer (a count or a rule).
  bool integral() const { return kind != Kind::kReal; }
};

/// A described struct as the group a file stores it in: the group's name and its entries.
struct Record {
  std::string name;            ///< the HDF5 group, e.g. "event_policy"
  std::vector<Entry> entries;  ///< every member, in the order of Describe
};

/// A member's full name: the prefix of the described structs it sits in, then its own.
struct Name {
  std::string_view prefix;  ///< "" or, for a member of a nested struct, e.g. "contact."
  const char* member;       ///< the member's own name

  /// prefix + member.
  std::string Full() const { return std::string(prefix).append(member); }
};

/// The archive every use below is made of: it walks a struct's description and hands each
/// number member to `on_member(const Name&, Kind, const Meta&, double& value)`, which returns
/// whether to write `value` back. Reals are visited in place; counts and rules through a
/// double. Nothing is allocated on the way (a nested prefix is built once, short), so a
/// validation costs a few comparisons per member.
template <typename OnMember>
class Walker {
 public:
  /// Walks with `on_member`, under `prefix` ("" at the top).
  explicit Walker(OnMember& on_member, std::string_view prefix = {})
      : on_member_(on_member), prefix_(prefix) {}

  /// A real-valued member.
  void Visit(NameValue<double> nv, const Meta& meta) {
    on_member_(Name{prefix_, nv.name}, Kind::kReal, meta, *nv.value);
  }
  /// A count.
  template <std::integral T>
  requires(!std::same_as<T, bool>) void Visit(NameValue<T> nv, const Meta& meta) {
    double v = static_cast<double>(*nv.value);
    if (on_member_(Name{prefix_, nv.name}, Kind::kCount, meta, v)) {
      *nv.value = static_cast<T>(v);
    }
  }
  /// A rule, stored as 1 (on) or 0 (off).
  void Visit(NameValue<bool> nv) {
    double v = *nv.value ? 1.0 : 0.0;
    if (on_member_(Name{prefix_, nv.name}, Kind::kRule, Meta{"1", "", Interval::Closed(0, 1)}, v)) {
      *nv.value = v != 0.0;
    }
  }
  /// A described struct held as a member: its members under the prefix "name.".
  template <typename T>
  requires(!std::is_arithmetic_v<T>) void Visit(NameValue<T> nv) {
    const std::string prefix = std::string(prefix_).append(nv.name).append(".");
    Walker inner(on_member_, prefix);
    nv.value->Describe(&inner);
  }

 private:
  OnMember& on_member_;
  std::string_view prefix_;
};

/// Walks the description of `object` with `on_member` (Walker).
template <typename T, typename OnMember>
void Walk(T& object, OnMember on_member) {
  Walker<OnMember> walker(on_member);
  object.Describe(&walker);
}

namespace detail {
// Converts to any type (declared only: used in unevaluated contexts).
struct AnyMember {
  template <typename T>
  operator T() const;
};
template <typename T, std::size_t... I>
constexpr bool BraceInitialisable(std::index_sequence<I...>) {
  return requires { T{(static_cast<void>(I), AnyMember{})...}; };
}
// Counts the top-level Visit calls of a description.
struct CountingArchive {
  std::size_t visits = 0;
  template <typename T>
  void Visit(NameValue<T>, const Meta&) {
    ++visits;
  }
  template <typename T>
  void Visit(NameValue<T>) {
    ++visits;
  }
};
}  // namespace detail

/// The number of members of the aggregate T: the largest N for which T{x_1, ..., x_N} is valid
/// with initialisers that convert to any type (no brace elision happens, since each converts
/// to the member's own type).
template <typename T, std::size_t N = 0>
constexpr std::size_t MemberCount() {
  if constexpr (detail::BraceInitialisable<T>(std::make_index_sequence<N + 1>{})) {
    return MemberCount<T, N + 1>();
  } else {
    return N;
  }
}

/// Whether the Describe of T visits as many members as T has (MemberCount): a member added to
/// the struct without its line in Describe makes this false (a test of each described struct
/// checks it).
template <typename T>
bool DescribesEveryMember() {
  T object{};
  detail::CountingArchive counter;
  object.Describe(&counter);
  return counter.visits == MemberCount<T>();
}

/// Every member of `object`, in the order of its Describe.
template <typename T>
std::vector<Entry> Entries(const T& object) {
  T copy = object;
  std::vector<Entry> out;
  Walk(copy, [&](const Name& name, Kind kind, const Meta& meta, double& value) {
    out.push_back({name.Full(), value, kind, meta.unit, meta.relative_to, meta.allowed});
    return false;
  });
  return out;
}

/// `object` as the group `name` of a file.
template <typename T>
Record ToRecord(std::string name, const T& object) {
  return {std::move(name), Entries(object)};
}

/// The first member of `object` outside what its description allows, as "member: must be
/// ALLOWED (got VALUE)"; nullopt when every member is allowed. Allocates only on a failure.
template <typename T>
std::optional<std::string> FirstViolation(const T& object);

/// Checks every member of `object` against its description.
/// @throws InputError "SOURCE: member: must be ALLOWED (got VALUE)" for the first member outside
/// (e.g. "event policy: finite_check_steps: must be a power of two (1, 2, 4, ...) (got 10)").
template <typename T>
void Validate(const T& object, std::string_view source);

/// Sets each member of `object` that `lookup(name)` gives a value for; returns the names
/// `lookup` had no value for (a stored group read back: the members a file lacks).
template <typename T>
std::vector<std::string> Assign(
    T* object, const std::function<std::optional<double>(const std::string&)>& lookup);

/// The Markdown rows documenting `defaults`, one per member in the order of its Describe:
/// "| `name` | default | unit | relative to | allowed |" (a rule's default "on" or "off"; a '|'
/// within a cell escaped as "\|").
/// The documentation's tables hold these cells; a test compares them.
template <typename T>
std::vector<std::string> MarkdownRows(const T& defaults);

/// `x` with the fewest significant digits that read back as x: an integer below 1e5 as one
/// ("64"), else as %g writes it with a short exponent ("1e-10", "1.5e-8", "2e6", "0.9").
std::string FormatNumber(double x);

/// The Markdown row of one entry (MarkdownRows).
std::string MarkdownRow(const Entry& entry);

/// "member: must be ALLOWED (got VALUE)", for a member outside what is allowed.
std::string Violation(const std::string& name, const Interval& allowed, double value);

/// Throws InputError "SOURCE: problem".
[[noreturn]] void ThrowInvalid(std::string_view source, const std::string& problem);

// --- Implementation ---

template <typename T>
std::optional<std::string> FirstViolation(const T& object) {
  T copy = object;
  std::optional<std::string> first;
  Walk(copy, [&](const Name& name, Kind, const Meta& meta, double& value) {
    if (!first && !meta.allowed.Admits(value)) first = Violation(name.Full(), meta.allowed, value);
    return false;
  });
  return first;
}

template <typename T>
void Validate(const T& object, std::string_view source) {
  if (const std::optional<std::string> problem = FirstViolation(object)) {
    ThrowInvalid(source, *problem);
  }
}

template <typename T>
std::vector<std::string> Assign(
    T* object, const std::function<std::optional<double>(const std::string&)>& lookup) {
  std::vector<std::string> missing;
  Walk(*object, [&](const Name& name, Kind, const Meta&, double& value) {
    const std::optional<double> v = lookup(name.Full());
    if (!v) {
      missing.push_back(name.Full());
      return false;
    }
    value = *v;
    return true;
  });
  return missing;
}

template <typename T>
std::vector<std::string> MarkdownRows(const T& defaults) {
  std::vector<std::string> rows;
  for (const Entry& e : Entries(defaults)) rows.push_back(MarkdownRow(e));
  return rows;
}

}  // namespace skewbridge::schema

/// A NameValue for the member `x` of the struct whose Describe is running: its name as written
/// and its address (DRAKE_NVP's idea).
#define SB_NVP(x) \
  ::skewbridge::schema::NameValue<std::remove_reference_t<decltype(x)>> { #x, &(x) }
