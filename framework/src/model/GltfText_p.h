#pragma once
/// \file GltfText_p.h
/// Private to the glTF loader: text from the file (URIs, tinygltf's messages quoting it) made
/// safe for error messages.

#include <string>
#include <string_view>

namespace mvcl::gltf {

/// At most `maxBytes` of `text`, with control characters and bytes that are not part of valid
/// UTF-8 written as \xNN, and "..." when cut: an error message never carries raw file bytes.
inline std::string printableText(std::string_view text, std::size_t maxBytes = 200) {
    static const char *kHex = "0123456789abcdef";
    std::string out;
    const std::size_t n = std::min(text.size(), maxBytes);
    const auto escape = [&](unsigned char c) {
        out += "\\x";
        out += kHex[c >> 4];
        out += kHex[c & 15];
    };
    for (std::size_t i = 0; i < n;) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) {
            escape(c);
            ++i;
            continue;
        }
        if (c < 0x80) {
            out += char(c);
            ++i;
            continue;
        }
        // A UTF-8 sequence: lead byte, then 1–3 continuation bytes, all inside the cut.
        const std::size_t len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
        bool valid = len > 0 && i + len <= n && !(c == 0xC0 || c == 0xC1);
        for (std::size_t k = 1; valid && k < len; ++k)
            valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
        if (valid) {
            out.append(text.substr(i, len));
            i += len;
        } else {
            escape(c);
            ++i;
        }
    }
    return text.size() > maxBytes ? out + "..." : out;
}

} // namespace mvcl::gltf
