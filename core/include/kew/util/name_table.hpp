#pragma once
// One table of names per enum. A configuration file, a command-line flag, a log line and
// an "expected one of ..." message all take their words from the same table, so that
// what is printed can always be parsed back and no list of choices falls out of date.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kew::util {

template <class Enum, std::size_t N>
class NameTable {
 public:
  struct Entry {
    Enum value;
    std::string_view name;
  };

  /// `entries`: every value of the enum once, each with a distinct name, in the order
  /// lists are printed.
  constexpr explicit NameTable(const std::array<Entry, N>& entries) : entries_(entries) {}

  /// The name of `value`. A value missing from the table (a cast integer) gets the
  /// first entry's name, so printing never fails.
  constexpr std::string_view name(Enum value) const {
    for (const Entry& e : entries_)
      if (e.value == value) return e.name;
    return entries_[0].name;
  }

  /// True when `value` is in the table (false only for an integer cast to Enum).
  constexpr bool contains(Enum value) const {
    for (const Entry& e : entries_)
      if (e.value == value) return true;
    return false;
  }

  /// The value named exactly `text` (case-sensitive), or nullopt.
  constexpr std::optional<Enum> parse(std::string_view text) const {
    for (const Entry& e : entries_)
      if (e.name == text) return e.value;
    return std::nullopt;
  }

  /// The names in table order, joined by ", " ("exact, edges, brute"), leaving out
  /// `except`: for help texts and error messages.
  std::string list(std::initializer_list<Enum> except = {}) const {
    std::string out;
    for (const std::string_view name : names(except)) {
      if (!out.empty()) out += ", ";
      out += name;
    }
    return out;
  }

  /// The names in table order, leaving out `except` (e.g. for a flag's allowed values).
  std::vector<std::string> names(std::initializer_list<Enum> except = {}) const {
    std::vector<std::string> out;
    for (const Entry& e : entries_) {
      bool skipped = false;
      for (const Enum x : except) skipped = skipped || x == e.value;
      if (!skipped) out.emplace_back(e.name);
    }
    return out;
  }

  constexpr const std::array<Entry, N>& entries() const { return entries_; }

 private:
  std::array<Entry, N> entries_;
};

}  // namespace kew::util
