#pragma once
// Values of the apps' command-line options, checked the same way in mvcl-render and the
// benches: CLI11 validators that say what was expected and what was given, and the parsers
// they check with. Header-only; apps/common/CMakeLists.txt makes it the mvcl-app-common target.

#include <mvcl/core/Error.h>

#include <CLI/CLI.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mvcl::cli {

/// What a value should have been, for CLI11 to report as "--option: problem".
class BadValue : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

inline std::string quotedValue(std::string_view text) {
    std::string quoted(1, '\'');
    quoted.append(text).push_back('\'');
    return quoted;
}

inline int parseWholeNumber(std::string_view text, int minimum, int maximum) {
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < minimum || value > maximum)
        throw BadValue("expects a whole number in " + std::to_string(minimum) + ".." + std::to_string(maximum) +
                       ", got " + quotedValue(text));
    return value;
}

inline double parseFiniteNumber(std::string_view text) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(float(value)))
        throw BadValue("expects a finite number, got " + quotedValue(text));
    return value;
}

/// "WxH", each side 1..16384.
inline glm::ivec2 parseImageSize(std::string_view text) {
    const std::size_t x = text.find('x');
    if (x == std::string_view::npos) throw BadValue("expects WxH, got " + quotedValue(text));
    return {parseWholeNumber(text.substr(0, x), 1, 16384), parseWholeNumber(text.substr(x + 1), 1, 16384)};
}

/// "x,y,z".
inline glm::vec3 parseVector3(std::string_view text) {
    std::vector<std::string_view> parts;
    for (std::size_t start = 0;;) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (parts.size() != 3) throw BadValue("expects x,y,z, got " + quotedValue(text));
    return {float(parseFiniteNumber(parts[0])), float(parseFiniteNumber(parts[1])), float(parseFiniteNumber(parts[2]))};
}

/// A CLI11 validator from a parser that throws BadValue; `description` is shown as the value's
/// name in --help (e.g. N, WxH).
template <class Parse> CLI::Validator validatorFrom(Parse parse, const std::string &description) {
    return CLI::Validator(
        [parse](std::string &text) {
            try {
                parse(text);
            } catch (const BadValue &e) {
                return std::string(e.what());
            }
            return std::string();
        },
        description);
}

inline CLI::Validator wholeNumberIn(int minimum, int maximum) {
    return validatorFrom([=](const std::string &text) { parseWholeNumber(text, minimum, maximum); }, "");
}

/// A finite number in the open interval (low, high).
inline CLI::Validator numberBetween(double low, double high, const std::string &what) {
    return validatorFrom(
        [=](const std::string &text) {
            const double value = parseFiniteNumber(text);
            if (!(value > low && value < high)) throw BadValue("must be " + what + ", got " + quotedValue(text));
        },
        "");
}

inline CLI::Validator imageSize() { return validatorFrom([](const std::string &text) { parseImageSize(text); }, ""); }
inline CLI::Validator vector3() { return validatorFrom([](const std::string &text) { parseVector3(text); }, ""); }

/// `--size WxH` into width and height, checked.
inline CLI::Option *addImageSizeOption(CLI::App &app, int &width, int &height, const std::string &description) {
    return app
        .add_option_function<std::string>(
            "--size",
            [&width, &height](const std::string &text) {
                const glm::ivec2 size = parseImageSize(text);
                width = size.x;
                height = size.y;
            },
            description)
        ->type_name("WxH")
        ->check(imageSize());
}

/// The way CLI11 shows a help screen here: the app's own usage lines instead of CLI11's
/// generated one, option names in a column wide enough for "--target-error E".
class UsageFormatter : public CLI::Formatter {
public:
    explicit UsageFormatter(std::string usage) : m_usage(std::move(usage)) { column_width(26); }
    std::string make_usage(const CLI::App *, std::string) const override { return "\n" + m_usage + "\n"; }

private:
    std::string m_usage;
};

/// Parses `args` (without the program name) with `app`. Help requests come back as true; any
/// problem throws mvcl::Error("command line", "<problem> (see <program> --help)").
inline bool parseCommandLine(CLI::App &app, std::vector<std::string> args) {
    std::reverse(args.begin(), args.end()); // CLI11 takes the arguments last first
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp &) {
        return true;
    } catch (const CLI::ParseError &e) {
        throw Error("command line", std::string(e.what()) + " (see " + app.get_name() + " --help)");
    } catch (const BadValue &e) { // thrown by an option's callback
        throw Error("command line", std::string(e.what()) + " (see " + app.get_name() + " --help)");
    }
    return false;
}

} // namespace mvcl::cli
