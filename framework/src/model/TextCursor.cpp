#include "TextCursor_p.h"

#include <algorithm>
#include <charconv>

namespace mvcl::meshfile {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

} // namespace

TextCursor::TextCursor(const ReadInput &input, std::size_t offset)
    : m_input(input), m_text(reinterpret_cast<const char *>(input.bytes.data()), input.bytes.size()),
      m_pos(std::min(offset, input.bytes.size())) {}

bool TextCursor::skipSpace() {
    while (m_pos < m_text.size() && isSpace(m_text[m_pos])) ++m_pos;
    return m_pos < m_text.size();
}

bool TextCursor::skipSpaceOnLine() {
    while (m_pos < m_text.size() && m_text[m_pos] != '\n' && isSpace(m_text[m_pos])) ++m_pos;
    return m_pos < m_text.size() && m_text[m_pos] != '\n';
}

std::string_view TextCursor::peekWord() {
    skipSpace();
    std::size_t end = m_pos;
    while (end < m_text.size() && !isSpace(m_text[end])) ++end;
    return m_text.substr(m_pos, end - m_pos);
}

std::string_view TextCursor::word() {
    const std::string_view w = peekWord();
    if (w.empty()) failAt("the file ends too early");
    m_pos += w.size();
    return w;
}

void TextCursor::expectWord(std::string_view expected) {
    const std::string_view w = word();
    if (w != expected) failAt("expected '" + std::string(expected) + "', found '" + std::string(w.substr(0, 40)) + "'");
}

double TextCursor::number() {
    const std::string_view w = word();
    std::string_view digits = w;
    if (digits.starts_with('+')) digits.remove_prefix(1); // from_chars takes no '+'
    double value = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec != std::errc() || end != digits.data() + digits.size())
        failAt("expected a number, found '" + std::string(w.substr(0, 40)) + "'");
    return value;
}

std::uint64_t TextCursor::count(std::uint64_t limit, const std::string &what) {
    const std::string_view w = word();
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (ec != std::errc() || end != w.data() + w.size())
        failAt(what + " is '" + std::string(w.substr(0, 40)) + "', not a count");
    if (value > limit) failAt(what + " is " + std::to_string(value) + ", more than " + std::to_string(limit));
    return value;
}

std::string TextCursor::restOfLine() {
    std::size_t end = m_pos;
    while (end < m_text.size() && m_text[end] != '\n') ++end;
    std::string_view line = m_text.substr(m_pos, end - m_pos);
    m_pos = std::min(end + 1, m_text.size());
    while (!line.empty() && isSpace(line.front())) line.remove_prefix(1);
    while (!line.empty() && isSpace(line.back())) line.remove_suffix(1);
    return std::string(line);
}

void TextCursor::failAt(const std::string &problem) const {
    const std::size_t line = 1 + std::size_t(std::count(m_text.begin(), m_text.begin() + std::ptrdiff_t(m_pos), '\n'));
    fail(m_input, "line " + std::to_string(line) + ": " + problem);
}

bool looksLikeText(std::span<const std::uint8_t> bytes) {
    const std::size_t n = std::min<std::size_t>(bytes.size(), 1024);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t c = bytes[i];
        if (c < 0x20 && !isSpace(char(c))) return false;
    }
    return true;
}

bool startsWithWord(std::span<const std::uint8_t> bytes, std::string_view word) {
    std::size_t i = 0;
    while (i < bytes.size() && isSpace(char(bytes[i]))) ++i;
    if (bytes.size() - i < word.size()) return false;
    if (std::string_view(reinterpret_cast<const char *>(bytes.data() + i), word.size()) != word) return false;
    return i + word.size() == bytes.size() || isSpace(char(bytes[i + word.size()]));
}

} // namespace mvcl::meshfile
