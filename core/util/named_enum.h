#pragma once
// Enumerations whose values have names in files and on the command line (config.json, `--set KEY=VALUE`):
// a specialisation of EnumNames<E> lists every value with its name once, and the configuration reads,
// writes and documents the setting from that list.
//
//   enum class Colour { Red, Green };
//   template <> struct EnumNames<Colour> {
//     static constexpr std::array<std::pair<Colour, const char*>, 2> names{{{Colour::Red, "red"}, {Colour::Green, "green"}}};
//   };
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace goris {

template <class E>
struct EnumNames;  // specialised per enumeration: `static constexpr std::array<std::pair<E, const char*>, N> names`

template <class E>
const char* enum_name(E value) {
  for (const auto& [v, name] : EnumNames<E>::names)
    if (v == value) return name;
  return "?";
}

template <class E>
std::optional<E> enum_from_name(std::string_view name) {
  for (const auto& [v, n] : EnumNames<E>::names)
    if (name == n) return v;
  return std::nullopt;
}

// "a, b or c": the names, for messages and the reference page.
template <class E>
std::string enum_choices() {
  std::string out;
  const auto& names = EnumNames<E>::names;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].second;
  return out;
}

}  // namespace goris
