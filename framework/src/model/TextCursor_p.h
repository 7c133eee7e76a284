#pragma once
/// \file TextCursor_p.h
/// Reading the ASCII mesh formats (STL, PLY) word by word: whitespace-separated words, numbers
/// parsed exactly (std::from_chars, no locale), errors that name the file and the line.

#include "MeshFileData_p.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace mvcl::meshfile {

class TextCursor {
public:
    explicit TextCursor(const ReadInput &input, std::size_t offset = 0);

    /// Skips whitespace; false at the end of the text.
    bool skipSpace();
    /// Skips spaces and tabs (and a carriage return) but not a line feed; false at the end of
    /// the line or of the text.
    bool skipSpaceOnLine();
    /// The next word; fails at the end of the text.
    std::string_view word();
    /// The next word without consuming it; empty at the end.
    std::string_view peekWord();
    /// Consumes the next word, failing unless it is `expected`.
    void expectWord(std::string_view expected);
    /// The next word as a number (decimal, exponent; "nan" and "inf" parse and are left for the
    /// caller's finiteness check to name).
    double number();
    /// The next word as an integer in [0, limit]; `what` names it in errors.
    std::uint64_t count(std::uint64_t limit, const std::string &what);
    /// The rest of the current line, trimmed; moves to the next line.
    std::string restOfLine();
    /// Bytes not yet read.
    std::size_t remaining() const { return m_text.size() - m_pos; }
    std::size_t position() const { return m_pos; }

    /// Throws the reader's error with the current line number.
    [[noreturn]] void failAt(const std::string &problem) const;

private:
    const ReadInput &m_input;
    std::string_view m_text;
    std::size_t m_pos = 0;
};

/// No NUL and no control characters other than whitespace in the first kilobyte.
bool looksLikeText(std::span<const std::uint8_t> bytes);
/// The text starts (after whitespace) with `word` followed by whitespace or the end.
bool startsWithWord(std::span<const std::uint8_t> bytes, std::string_view word);

} // namespace mvcl::meshfile
