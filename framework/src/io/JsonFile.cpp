#include "JsonFile_p.h"

#include <mvcl/lens/Lens.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

namespace mvcl::detail {

namespace {

void appendPretty(const Json &value, int indent, std::string &out) {
    if (value.is_object() && !value.empty()) {
        const std::string inner(std::size_t(indent + 2), ' ');
        out += "{\n";
        bool first = true;
        for (const auto &[key, member] : value.items()) {
            out.append(first ? "" : ",\n").append(inner).append(Json(key).dump()).append(": ");
            appendPretty(member, indent + 2, out);
            first = false;
        }
        out.append("\n").append(std::size_t(indent), ' ').append("}");
    } else if (value.is_array() && std::ranges::any_of(value, [](const Json &e) { return e.is_object(); })) {
        const std::string inner(std::size_t(indent + 2), ' ');
        out += "[\n";
        for (std::size_t i = 0; i < value.size(); ++i) {
            out.append(i ? ",\n" : "").append(inner);
            appendPretty(value[i], indent + 2, out);
        }
        out.append("\n").append(std::size_t(indent), ' ').append("]");
    } else if (value.is_array() && !value.empty()) {
        out += "[";
        for (std::size_t i = 0; i < value.size(); ++i) {
            out.append(i ? ", " : "");
            appendPretty(value[i], indent, out);
        }
        out += "]";
    } else {
        out += value.dump();
    }
}

/// Writes everything or fails with errno set.
bool writeAll(int fd, std::string_view text) {
    while (!text.empty()) {
        const ssize_t written = ::write(fd, text.data(), text.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return false;
        text.remove_prefix(std::size_t(written));
    }
    return true;
}

} // namespace

std::string joined(std::span<const std::string_view> names) {
    std::string text;
    for (std::string_view name : names) text.append(text.empty() ? "" : ", ").append(name);
    return text;
}

const Json &expectObject(const Json &value, const JsonLocation &where) {
    if (!value.is_object()) where.fail(std::string("expected an object, got ") + value.type_name());
    return value;
}

void expectVersion(const Json &document, int version, const JsonLocation &where) {
    if (!document.contains("version")) return;
    const Json &value = document["version"];
    if (!value.is_number_integer() || value.get<long long>() != version)
        where.key("version").fail("this build reads version " + std::to_string(version) + ", got " + value.dump());
}

void rejectUnknownKeys(const Json &object, std::span<const std::string_view> known,
                       const JsonLocation &where) {
    for (const auto &[key, value] : object.items())
        if (std::find(known.begin(), known.end(), key) == known.end())
            where.fail("unknown key '" + key + "' (known: " + joined(known) + ")");
}

std::string readString(const Json &value, const JsonLocation &where) {
    if (!value.is_string()) where.fail(std::string("expected a string, got ") + value.type_name());
    return value.get<std::string>();
}

bool readBool(const Json &value, const JsonLocation &where) {
    if (!value.is_boolean()) where.fail(std::string("expected true or false, got ") + value.dump());
    return value.get<bool>();
}

float readNumber(const Json &value, const JsonLocation &where) {
    if (!value.is_number()) where.fail("expected a number, got " + value.dump());
    const double number = value.get<double>();
    if (!std::isfinite(float(number))) where.fail("number " + value.dump() + " is out of range");
    return float(number);
}

std::string propertyText(const Json &value, const JsonLocation &where) {
    if (value.is_string()) return value.get<std::string>();
    if (value.is_number() || value.is_boolean()) return value.dump();
    if (!value.is_array())
        where.fail(std::string("expected a string, number, boolean or array, got ") + value.type_name());
    std::string text;
    for (std::size_t i = 0; i < value.size(); ++i) {
        const Json &element = value[i];
        if (element.is_array() || element.is_object() || element.is_null())
            where.index(i).fail("expected a string or number, got " + element.dump());
        text.append(i ? "," : "").append(element.is_string() ? element.get<std::string>() : element.dump());
    }
    return text;
}

double shortestDouble(float value) {
    char text[32];
    const auto printed = std::to_chars(text, text + sizeof text, value);
    double result = value;
    std::from_chars(text, printed.ptr, result);
    return result;
}

std::string unknownPropertyMessage(const std::string &key, const Lens &lens) {
    std::string known;
    for (const PropertyDecl &decl : lens.properties()) known.append(known.empty() ? "" : ", ").append(decl.name);
    return "unknown property '" + key + "' of lens '" + lens.typeName() + "' (known: " + known + ")";
}

std::string prettyJson(const Json &value) {
    std::string text;
    appendPretty(value, 0, text);
    return text;
}

Json parseJsonDocument(std::string_view text, const std::string &sourceName) {
    try {
        return Json::parse(text);
    } catch (const Json::exception &e) {
        // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep line and column.
        std::string message = e.what();
        if (const std::size_t close = message.find("] "); message.starts_with("[json.") && close != std::string::npos)
            message.erase(0, close + 2);
        throw Error(sourceName, "invalid JSON: " + message);
    }
}

std::string readTextFile(const std::filesystem::path &path, const std::string &what) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(name, "is a folder, not a " + what);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(name, "cannot open the " + what + ": " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

namespace {

std::atomic<unsigned> g_nextTemporary{0};

/// Temporary files of `path` ("<file>.part-<pid>-<n>") whose writing process no longer runs: a
/// process killed between creating one and renaming it leaves it behind. A process still running
/// may be writing its own, and files of another form are not ours: both are left alone.
void removeTemporariesOfGoneWriters(const std::filesystem::path &path) {
    const std::string prefix = path.filename().string() + ".part-";
    std::error_code ec;
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    for (const std::filesystem::directory_entry &entry : std::filesystem::directory_iterator(folder, ec)) {
        const std::string file = entry.path().filename().string();
        if (file.rfind(prefix, 0) != 0) continue;
        long pid = 0;
        const char *first = file.data() + prefix.size(), *last = file.data() + file.size();
        const auto [end, error] = std::from_chars(first, last, pid);
        if (error != std::errc() || end == last || *end != '-' || pid <= 0) continue;
        if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove(entry.path(), ec);
    }
}

} // namespace

void writeFileAtomically(const std::filesystem::path &path, std::string_view text) {
    const std::string name = path.string();
    if (path.has_parent_path()) {
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) throw Error(name, "cannot create folder: " + ec.message());
    }
    // Named after this process, so that a later write can tell a file left by a killed writer.
    std::string temp;
    int fd = -1;
    for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
        temp = name + ".part-" + std::to_string(::getpid()) + "-" + std::to_string(g_nextTemporary++);
        fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) throw Error(name, std::string("cannot create a temporary file next to it: ") + std::strerror(errno));
    const auto failWith = [&](const std::string &what) {
        const int error = errno;
        ::unlink(temp.c_str());
        throw Error(name, what + ": " + std::strerror(error));
    };
    ::fchmod(fd, 0644); // a session file is an ordinary document, whatever the umask
    if (!writeAll(fd, text) || ::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        errno = error;
        failWith("write failed");
    }
    if (::close(fd) != 0) failWith("write failed");
    if (::rename(temp.c_str(), name.c_str()) != 0) failWith("cannot replace the file");
    removeTemporariesOfGoneWriters(path);
}

} // namespace mvcl::detail
