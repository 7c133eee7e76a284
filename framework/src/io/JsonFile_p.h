#pragma once
/// \file JsonFile_p.h
/// Private to the io module: what the JSON files of mvcl (lens-stack files, animation files)
/// share when they are read — values checked with errors that name the file and the JSON path
/// — and when they are written: compact arrays, shortest float text, atomic replacement.

#include <mvcl/core/Error.h>

#include <nlohmann/json.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace mvcl {
class Lens;
} // namespace mvcl

namespace mvcl::detail {

// Ordered, so written files keep the natural key order and properties stay in table order.
using Json = nlohmann::ordered_json;

/// "a, b, c".
std::string joined(std::span<const std::string_view> names);

/// Where a value sits, for error messages: the file (or option) and the JSON path in it.
/// On the command line the structure ("region", "properties") is implicit, so only leaf keys
/// show up in the path.
struct JsonLocation {
    std::string source;
    std::string path;
    bool commandLine = false;

    JsonLocation key(std::string_view name) const {
        std::string child = path;
        child.append(path.empty() ? "" : (commandLine ? ": " : ".")).append(name);
        return {source, std::move(child), commandLine};
    }
    JsonLocation section(std::string_view name) const { return commandLine ? *this : key(name); }
    JsonLocation index(std::size_t i) const {
        return {source, path + "[" + std::to_string(i) + "]", commandLine};
    }
    [[noreturn]] void fail(const std::string &problem) const {
        throw Error(source, path.empty() ? problem : path + ": " + problem);
    }
};

const Json &expectObject(const Json &value, const JsonLocation &where);
/// The document's optional "version" must be `version`, the one this build reads and writes.
void expectVersion(const Json &document, int version, const JsonLocation &where);
void rejectUnknownKeys(const Json &object, std::span<const std::string_view> known, const JsonLocation &where);
std::string readString(const Json &value, const JsonLocation &where);
bool readBool(const Json &value, const JsonLocation &where);
/// A finite number that fits a float.
float readNumber(const Json &value, const JsonLocation &where);

template <int N>
inline glm::vec<N, float> readVector(const Json &value, const JsonLocation &where) {
    if (!value.is_array() || value.size() != std::size_t(N))
        where.fail("expected an array of " + std::to_string(N) + " numbers, got " + value.dump());
    glm::vec<N, float> v;
    for (int i = 0; i < N; ++i) v[i] = readNumber(value[std::size_t(i)], where.index(std::size_t(i)));
    return v;
}

/// A property value as the text its declaration parses: strings as they are, numbers and
/// booleans in their JSON spelling, arrays as comma-separated elements ([r,g,b], [1,2]).
std::string propertyText(const Json &value, const JsonLocation &where);

/// "unknown property 'key' of lens 'type' (known: a, b, ...)".
std::string unknownPropertyMessage(const std::string &key, const Lens &lens);

/// The double that prints as the shortest text reading back to `value` as a float, so files
/// say 0.3 and not 0.30000001192092896.
double shortestDouble(float value);

template <int N>
inline Json vectorJson(const glm::vec<N, float> &v) {
    Json array = Json::array();
    for (int i = 0; i < N; ++i) array.push_back(shortestDouble(v[i]));
    return array;
}

/// Indented JSON with arrays of numbers and points kept on one line, as a person would write
/// these files ("center": [0.5, 0.5] rather than one number per line).
std::string prettyJson(const Json &value);

/// The document in `text`; throws mvcl::Error(sourceName, "invalid JSON: ... line, column").
Json parseJsonDocument(std::string_view text, const std::string &sourceName);
/// The whole file; throws mvcl::Error(path, "cannot open the <what>: reason") (also for a folder).
std::string readTextFile(const std::filesystem::path &path, const std::string &what);

/// Temporary file in the same folder (so rename is atomic), flushed to disk, then renamed over
/// `path`: readers see the old file or the new one, never a torn one. The temporary file is
/// "<file>.part-<pid>-<n>"; after the rename, those of processes that no longer run (killed
/// mid-write) are removed. Throws mvcl::Error(path, ...).
void writeFileAtomically(const std::filesystem::path &path, std::string_view text);

} // namespace mvcl::detail
