#pragma once
/// \file PropertyText_p.h
/// Small text helpers shared by the property parser and printer (internal).

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

namespace mvcl::detail {

inline bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

inline std::string_view trimmed(std::string_view text) {
    while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
    return text;
}

inline std::string lowered(std::string_view text) {
    std::string result(text);
    for (char &c : result)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return result;
}

inline std::string quoted(std::string_view text) {
    std::string result(1, '"'); // appended piecewise: GCC 12 warns falsely on "\"" + string
    result += text;
    result += '"';
    return result;
}

/// Shortest text that reads back to exactly `value` (std::to_chars guarantees the round trip).
template <typename Number> std::string shortestText(Number value) {
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

/// Infinite bounds print as ∞ so range texts read naturally ("[0, ∞)").
inline std::string boundText(double value) {
    if (std::isinf(value)) return value < 0 ? "-∞" : "∞";
    return shortestText(value);
}

/// Strict: the whole of `text` must be the number (no spaces, no trailing junk).
template <typename Number> bool parseWhole(std::string_view text, Number &value) {
    if (text.empty()) return false;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

} // namespace mvcl::detail
