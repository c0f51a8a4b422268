// Scene loading: built-in names, scene files (JSON) and glTF 2.0 files.
//
// glTF: the default scene's node hierarchy (or every root node when there is no default scene) is
// flattened into object-space meshes (one per primitive, shared between the nodes that use the
// glTF mesh) and instances carrying each node's accumulated worldFromObject. Lights
// (KHR_lights_punctual) and cameras take their position and direction (-z) from the node's world
// transform. Anything the renderer cannot honour faithfully is rejected with an Error that names
// the file and the element, rather than loaded half-way.
//
// Scene files: see loadSceneFile below for the keys; every key is checked, unknown keys are errors.
#include "core/scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/scene/builtin_scenes.h"
#include "core/scene/image_downscale.h"
#include "core/util/error.h"
#include "core/util/warning.h"

namespace vplgi {

namespace {

namespace fs = std::filesystem;

constexpr float kPi = 3.14159265358979f;
// glTF zfar absent = infinite projection; our Camera wants a finite far plane [m].
constexpr float kInfiniteFar = 1.0e5f;

std::string lowerExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool isRegularFile(const std::string& path)
{
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

void requireFile(const std::string& path)
{
    std::error_code ec;
    require(fs::exists(path, ec), path + ": no such file");
    require(isRegularFile(path), path + ": not a regular file");
}

// First non-empty line of a (possibly multi-line) library message, trimmed.
std::string firstLine(const std::string& text)
{
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        const auto notSpace = [](unsigned char c) { return !std::isspace(c); };
        line.erase(line.begin(), std::find_if(line.begin(), line.end(), notSpace));
        line.erase(std::find_if(line.rbegin(), line.rend(), notSpace).base(), line.end());
        if (!line.empty()) return line;
    }
    return "";
}

std::string readWholeFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    require(static_cast<bool>(in), path + ": cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

// Appends "-2", "-3", ... until the name is unused; empty base names take the fallback.
std::string uniqueName(const std::string& preferred, const std::string& fallback, const std::set<std::string>& taken)
{
    const std::string base = preferred.empty() ? fallback : preferred;
    std::string name = base;
    for (int k = 2; taken.count(name) != 0; ++k)
        name = base + "-" + std::to_string(k);
    return name;
}

// Converts nlohmann's "[json.exception.parse_error.101] parse error at line 3, column 5: <why>"
// into "<where>:3:5: invalid JSON: <why>" (one line, compiler-style).
[[noreturn]] void throwJsonParseError(const std::string& where, const std::string& text,
                                      const nlohmann::json::parse_error& e)
{
    const std::size_t at = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    std::string why = e.what();
    const std::size_t start = why.find("parse error");
    const std::size_t colon = start == std::string::npos ? std::string::npos : why.find(": ", start);
    if (colon != std::string::npos) why = why.substr(colon + 2);
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw Error(where + ":" + std::to_string(line) + ":" + std::to_string(column) + ": invalid JSON: " + why);
}

// The parser's other errors, e.g. out_of_range 406 for a number beyond a double ("1e400"), found by
// fuzzing (tests/fuzz): "<where>: invalid JSON: number overflow parsing '1e400'", never nlohmann's
// own exception, which names no file.
[[noreturn]] void throwJsonError(const std::string& where, const nlohmann::json::exception& e)
{
    std::string why = e.what();
    const std::size_t tag = why.find("] "); // drops nlohmann's "[json.exception.out_of_range.406] "
    if (why.rfind("[json.exception.", 0) == 0 && tag != std::string::npos) why = why.substr(tag + 2);
    std::replace(why.begin(), why.end(), '\n', ' ');
    // A number too large for a double ("1e999") is how a JSON file spells a non-finite value (JSON
    // has no NaN or Inf).
    if (e.id == 406) why += " (numbers must be finite)";
    throw Error(where + ": invalid JSON: " + why);
}

// ---------------------------------------------------------------------------------------------
// glTF
// ---------------------------------------------------------------------------------------------

// Extensions whose meaning we implement (or which change nothing for us); any other extension in
// extensionsRequired makes the file unloadable.
const std::set<std::string>& supportedRequiredExtensions()
{
    static const std::set<std::string> kSupported = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular",
        "KHR_mesh_quantization", // integer attributes are converted generically below
        "KHR_texture_transform",
    };
    return kSupported;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb; empty when it cannot be found.
std::string_view gltfJsonText(const std::string& bytes, bool binary)
{
    if (!binary) return bytes;
    // Anything that is not a well-formed GLB header yields "", which parses as invalid JSON; let
    // tinygltf describe those files instead (see checkGltfDocument).
    if (bytes.size() < 20) return {};
    const auto u32 = [&](std::size_t offset) {
        std::uint32_t v = 0;
        std::memcpy(&v, bytes.data() + offset, 4); // glb is little-endian, as is every platform we build on
        return v;
    };
    if (u32(0) != 0x46546C67u || u32(16) != 0x4E4F534Au) return {}; // "glTF", "JSON"
    const std::size_t length = std::min(u32(12), u32(8));
    if (length > bytes.size() - 20) return {};
    return std::string_view(bytes).substr(20, length);
}

// "%2E%2E" -> "..": glTF URIs are percent-encoded (RFC 3986); checked in decoded form so that an
// encoded ".." cannot slip past the folder rule below.
std::string percentDecoded(const std::string& uri)
{
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// The one rule for external files, the buffers and images a glTF names by URI: the file, symbolic
// links resolved, must lie inside the glTF file's folder (`folder`, canonical) and, when it exists,
// be a regular file. A scene must not read files elsewhere on the machine (a downloaded asset naming
// "../../home/user/.ssh/id_rsa" as a texture) nor device files (/dev/zero never ends). Returns why
// `file` is refused, or "". Applied to every URI before tinygltf runs (checkGltfDocument, whose
// message names the buffer or image) and again to every file tinygltf opens (gltfReadWholeFile:
// tinygltf also searches the current directory).
std::string fileOutsideFolderReason(const fs::path& folder, const fs::path& file)
{
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(file, ec);
    const fs::path relative = ec ? fs::path("..") : resolved.lexically_relative(folder);
    if (relative.empty() || *relative.begin() == "..") return "points outside the scene's folder";
    if (fs::exists(resolved, ec) && !fs::is_regular_file(resolved, ec)) return "is not a regular file";
    return "";
}

// Why an external (non-data:) URI is refused, or "": only relative paths (percent-decoded, "\\" read
// as "/"), and then fileOutsideFolderReason.
std::string uriOutsideFolderReason(const fs::path& folder, const std::string& uri)
{
    std::string path = percentDecoded(uri);
    if (path.empty()) return "is empty";
    const std::size_t colon = path.find(':');
    const std::size_t slash = path.find_first_of("/\\");
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash)) return "is not a relative path";
    if (path[0] == '/' || path[0] == '\\') return "is an absolute path";
    std::replace(path.begin(), path.end(), '\\', '/');
    return fileOutsideFolderReason(folder, folder / path);
}

// Checks on the raw JSON, before tinygltf runs: an unsupported required extension often also makes
// tinygltf fail (KHR_texture_basisu images cannot be decoded), and its name is the message the user
// needs; external files outside the scene's folder must be refused before tinygltf opens them.
void checkGltfDocument(const std::string& path, const std::string& bytes, bool binary, const fs::path& folder)
{
    const std::string_view text = gltfJsonText(bytes, binary);
    if (binary && text.empty()) return;
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        // Reported like a scene file; in a .glb the position is within the JSON chunk.
        throwJsonParseError(binary ? path + ": JSON chunk" : path, std::string(text), e);
    } catch (const nlohmann::json::exception& e) {
        throwJsonError(binary ? path + ": JSON chunk" : path, e);
    }
    if (!doc.is_object()) return;
    auto it = doc.find("extensionsRequired");
    if (it != doc.end() && it->is_array())
        for (const nlohmann::json& ext : *it)
            if (ext.is_string() && supportedRequiredExtensions().count(ext.get<std::string>()) == 0)
                throw Error(path + ": unsupported required extension " + ext.get<std::string>());
    // glTF arrays and the singular that names one element in messages.
    for (const auto& [array, element] : {std::pair{"buffers", "buffer"}, std::pair{"images", "image"}}) {
        auto list = doc.find(array);
        if (list == doc.end() || !list->is_array()) continue;
        for (std::size_t i = 0; i < list->size(); ++i) {
            const nlohmann::json& item = (*list)[i];
            if (!item.is_object()) continue;
            auto uri = item.find("uri");
            if (uri == item.end() || !uri->is_string()) continue;
            const std::string uriText = uri->get<std::string>();
            if (uriText.rfind("data:", 0) == 0) continue;
            const std::string reason = uriOutsideFolderReason(folder, uriText);
            if (!reason.empty())
                throw Error(path + ": " + element + " " + std::to_string(i) + ": uri \"" + uriText + "\" " + reason +
                            " (refused: only data: URIs and files in the scene's folder are read)");
        }
    }
}

// tinygltf's file access for external buffers and images (URIs): fileOutsideFolderReason on every
// file it opens.
struct GltfFolder {
    fs::path canonical; // the folder, symlinks resolved
};

bool gltfFileExists(const std::string& path, void*)
{
    return isRegularFile(path);
}

std::string gltfExpandFilePath(const std::string& path, void*)
{
    return path; // no "~" or environment expansion: a URI names a file next to the glTF
}

bool gltfReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* userData)
{
    const GltfFolder& folder = *static_cast<const GltfFolder*>(userData);
    std::error_code ec;
    const fs::path file = fs::absolute(path, ec);
    std::string reason = ec ? "cannot be resolved" : fileOutsideFolderReason(folder.canonical, file);
    if (reason.empty() && !isRegularFile(file.string())) reason = "does not exist";
    if (!reason.empty()) {
        if (err != nullptr) *err += path + " " + reason + " (refused: only files in the scene's folder are read)";
        return false;
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        if (err != nullptr) *err += "cannot open";
        return false;
    }
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
}

bool gltfRefuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err != nullptr) *err += "vplgi never writes glTF files";
    return false;
}

// A typed window onto an accessor's elements, bounds-checked against its buffer.
struct AccessorView {
    const unsigned char* data = nullptr; // null: no bufferView, every element is zero (glTF rule)
    std::size_t stride = 0;
    std::size_t count = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;

    const unsigned char* element(std::size_t i, int component) const
    {
        return data + i * stride +
               static_cast<std::size_t>(component) *
                   static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(componentType));
    }
};

float readComponentAsFloat(const unsigned char* p, int componentType, bool normalized)
{
    // Normalized integer rules from the glTF 2.0 spec, section 3.11 (signed: max(c / max, -1)).
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, sizeof(v));
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t v;
        std::memcpy(&v, p, sizeof(v));
        return normalized ? std::max(static_cast<float>(v) / 127.0f, -1.0f) : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        std::uint8_t v;
        std::memcpy(&v, p, sizeof(v));
        return normalized ? static_cast<float>(v) / 255.0f : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, sizeof(v));
        return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof(v));
        return normalized ? static_cast<float>(v) / 65535.0f : static_cast<float>(v);
    }
    default: { // TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT (others are rejected in viewAccessor)
        std::uint32_t v;
        std::memcpy(&v, p, sizeof(v));
        return normalized ? static_cast<float>(static_cast<double>(v) / 4294967295.0) : static_cast<float>(v);
    }
    }
}

std::uint32_t readComponentAsIndex(const unsigned char* p, int componentType)
{
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof(v));
        return v;
    }
    default: {
        std::uint32_t v;
        std::memcpy(&v, p, sizeof(v));
        return v;
    }
    }
}

const char* modeName(int mode)
{
    switch (mode) {
    case TINYGLTF_MODE_POINTS:
        return "POINTS";
    case TINYGLTF_MODE_LINE:
        return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
        return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
        return "LINE_STRIP";
    default:
        return "unknown";
    }
}

// True when a triangle has (numerically) no area: two equal corners, collinear corners, or a height
// below 1e-6 of its longest edge. Below that the float cross product is mostly rounding error (a
// few 1e-7 relative), so the triangle's normal is noise, and its area is zero for anything that
// samples emitters by area (a density of 1/area).
bool isDegenerateTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c)
{
    const glm::vec3 ab = b - a, ac = c - a, bc = c - b;
    const float longestSquared = std::max({glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(bc, bc)});
    const float twiceArea = glm::length(glm::cross(ab, ac)); // = longest edge * height
    return !(twiceArea > 1e-6f * longestSquared);
}

// Removes mesh.indices' degenerate triangles (vertices stay); returns how many.
std::size_t dropDegenerateTriangles(Mesh& mesh)
{
    std::size_t kept = 0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        if (i0 == i1 || i1 == i2 || i0 == i2 ||
            isDegenerateTriangle(mesh.vertices[i0].position, mesh.vertices[i1].position, mesh.vertices[i2].position))
            continue;
        mesh.indices[kept++] = i0;
        mesh.indices[kept++] = i1;
        mesh.indices[kept++] = i2;
    }
    const std::size_t dropped = (mesh.indices.size() - kept) / 3;
    mesh.indices.resize(kept);
    return dropped;
}

class GltfImporter {
public:
    GltfImporter(const tinygltf::Model& model, const std::string& path, Scene& scene)
        : mModel(model), mPath(path), mScene(scene)
    {
    }

    void run()
    {
        for (std::size_t i = 0; i < mModel.images.size(); ++i)
            mScene.images.push_back(convertImage(i));
        for (std::size_t i = 0; i < mModel.materials.size(); ++i)
            mScene.materials.push_back(convertMaterial(i));
        warnAboutBlendMaterials();

        mVisiting.assign(mModel.nodes.size(), false);
        for (int root : rootNodes())
            visitNode(root, glm::mat4(1.0f));
        warnAboutDroppedTriangles();
    }

private:
    [[noreturn]] void fail(const std::string& what, const std::string& message) const
    {
        throw Error(mPath + ": " + what + ": " + message);
    }

    // One line per file however many primitives lost triangles: real-world assets can have
    // thousands of them, and the count is what the user needs.
    void warnAboutDroppedTriangles() const
    {
        if (mDroppedTriangles == 0) return;
        const auto plural = [](std::size_t n, const char* word) {
            return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
        };
        std::string message = mPath + ": dropped " + plural(mDroppedTriangles, "degenerate (zero-area) triangle") +
                              " in " + plural(mDroppedPrimitives, "primitive") + ", first in " + mFirstDropped;
        if (mDroppedEmissive > 0) message += "; " + std::to_string(mDroppedEmissive) + " of them emissive";
        if (mEmptiedPrimitives > 0) message += "; " + plural(mEmptiedPrimitives, "primitive") + " left empty";
        warn(message);
    }

    // One line per file: vplgi renders no transparency, so a BLEND material is cut at alpha 0.5.
    void warnAboutBlendMaterials() const
    {
        std::size_t count = 0;
        std::string first;
        for (std::size_t i = 0; i < mModel.materials.size(); ++i)
            if (mModel.materials[i].alphaMode == "BLEND" && count++ == 0)
                first = label("material", i, mModel.materials[i].name);
        if (count == 0) return;
        warn(mPath + ": " + std::to_string(count) + " material" + (count == 1 ? "" : "s") +
             " with alphaMode BLEND, first " + first + ": drawn as MASK at alphaCutoff 0.5 (no transparency)");
    }

    static std::string label(const char* kind, std::size_t index, const std::string& name)
    {
        return std::string(kind) + " " + std::to_string(index) + (name.empty() ? "" : " (" + name + ")");
    }

    std::vector<int> rootNodes() const
    {
        if (mModel.defaultScene >= 0) {
            if (static_cast<std::size_t>(mModel.defaultScene) >= mModel.scenes.size())
                throw Error(mPath + ": default scene " + std::to_string(mModel.defaultScene) + " does not exist");
            return mModel.scenes[static_cast<std::size_t>(mModel.defaultScene)].nodes;
        }
        std::vector<bool> isChild(mModel.nodes.size(), false);
        for (const tinygltf::Node& node : mModel.nodes)
            for (int child : node.children)
                if (child >= 0 && static_cast<std::size_t>(child) < isChild.size())
                    isChild[static_cast<std::size_t>(child)] = true;
        std::vector<int> roots;
        for (std::size_t i = 0; i < mModel.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(static_cast<int>(i));
        return roots;
    }

    // ---- images, textures, materials ----

    Image convertImage(std::size_t index) const
    {
        const tinygltf::Image& src = mModel.images[index];
        const std::string what = label("image", index, src.name.empty() ? src.uri : src.name);
        if (src.image.empty() || src.width <= 0 || src.height <= 0) fail(what, "could not be decoded");
        if (src.component < 1 || src.component > 4)
            fail(what, std::to_string(src.component) + " channels (need 1 to 4)");
        if (src.bits != 8 && src.bits != 16) fail(what, std::to_string(src.bits) + " bits per channel (need 8 or 16)");
        const std::size_t pixels = static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height);
        const std::size_t bytesPerChannel = static_cast<std::size_t>(src.bits / 8);
        const std::size_t channels = static_cast<std::size_t>(src.component);
        if (src.image.size() != pixels * channels * bytesPerChannel) fail(what, "pixel data has the wrong size");

        Image out;
        out.name = src.name.empty() ? src.uri : src.name;
        out.width = src.width;
        out.height = src.height;
        out.rgba.resize(pixels * 4);
        const auto channel = [&](std::size_t pixel, std::size_t c) -> std::uint8_t {
            const std::size_t at = (pixel * channels + c) * bytesPerChannel;
            if (bytesPerChannel == 1) return src.image[at];
            std::uint16_t v; // stb delivers native-endian 16-bit samples
            std::memcpy(&v, &src.image[at], sizeof(v));
            return static_cast<std::uint8_t>((static_cast<std::uint32_t>(v) * 255u + 32767u) / 65535u);
        };
        for (std::size_t p = 0; p < pixels; ++p) {
            std::uint8_t* dst = &out.rgba[p * 4];
            if (channels <= 2) { // grey (+ alpha)
                dst[0] = dst[1] = dst[2] = channel(p, 0);
                dst[3] = channels == 2 ? channel(p, 1) : 255;
            } else {
                dst[0] = channel(p, 0);
                dst[1] = channel(p, 1);
                dst[2] = channel(p, 2);
                dst[3] = channels == 4 ? channel(p, 3) : 255;
            }
        }
        downscaleToFit(out, kMaxImageEdge, what, "at most " + std::to_string(kMaxImageEdge) + " texels per edge");
        return out;
    }

    // A textureInfo (or normalTextureInfo): the texture, its UV set and its KHR_texture_transform.
    template <typename Info>
    TextureRef textureRef(const Info& info, const std::string& what) const
    {
        TextureRef ref;
        const int textureIndex = info.index;
        int texCoord = info.texCoord;
        if (textureIndex < 0) return ref;
        if (static_cast<std::size_t>(textureIndex) >= mModel.textures.size())
            fail(what, "texture " + std::to_string(textureIndex) + " does not exist");
        auto transform = info.extensions.find("KHR_texture_transform");
        if (transform != info.extensions.end()) {
            const tinygltf::Value& t = transform->second;
            if (!t.IsObject()) fail(what, "KHR_texture_transform must be an object");
            auto pair = [&](const char* key, glm::vec2 fallback) {
                if (!t.Has(key)) return fallback;
                const tinygltf::Value& v = t.Get(key);
                if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
                    fail(what, std::string("KHR_texture_transform ") + key + " must be 2 numbers");
                const glm::vec2 out(static_cast<float>(v.Get(0).GetNumberAsDouble()),
                                    static_cast<float>(v.Get(1).GetNumberAsDouble()));
                if (!std::isfinite(out.x) || !std::isfinite(out.y))
                    fail(what, std::string("KHR_texture_transform ") + key + " must be finite");
                return out;
            };
            ref.offset = pair("offset", glm::vec2(0.0f));
            ref.scale = pair("scale", glm::vec2(1.0f));
            if (t.Has("rotation")) {
                const tinygltf::Value& r = t.Get("rotation");
                if (!r.IsNumber() || !std::isfinite(r.GetNumberAsDouble()))
                    fail(what, "KHR_texture_transform rotation must be a finite number");
                ref.rotation = static_cast<float>(r.GetNumberAsDouble());
            }
            if (t.Has("texCoord")) {
                if (!t.Get("texCoord").IsInt()) fail(what, "KHR_texture_transform texCoord must be an integer");
                texCoord = t.Get("texCoord").GetNumberAsInt();
            }
        }
        if (texCoord != 0 && texCoord != 1)
            fail(what, "uses TEXCOORD_" + std::to_string(texCoord) + " (TEXCOORD_0 and TEXCOORD_1 are supported)");
        ref.texCoord = texCoord;
        const int source = mModel.textures[static_cast<std::size_t>(textureIndex)].source;
        if (source < 0) return ref; // no image we can decode: treated as untextured
        if (static_cast<std::size_t>(source) >= mModel.images.size())
            fail(what,
                 "texture " + std::to_string(textureIndex) + " refers to missing image " + std::to_string(source));
        ref.image = source;
        return ref;
    }

    // A number inside an extension object, or fallback when absent.
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const char* extension, const char* key,
                           double fallback, const std::string& what) const
    {
        auto it = extensions.find(extension);
        if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
        const tinygltf::Value& v = it->second.Get(key);
        if (!v.IsNumber()) fail(what, std::string(extension) + "." + key + " must be a number");
        return v.GetNumberAsDouble();
    }

    Material convertMaterial(std::size_t index) const
    {
        const tinygltf::Material& src = mModel.materials[index];
        const std::string what = label("material", index, src.name);
        const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;

        Material m;
        m.name = src.name.empty() ? "material" + std::to_string(index) : src.name;
        if (pbr.baseColorFactor.size() != 4) fail(what, "baseColorFactor must have 4 numbers");
        m.baseColor = glm::vec4(static_cast<float>(pbr.baseColorFactor[0]), static_cast<float>(pbr.baseColorFactor[1]),
                                static_cast<float>(pbr.baseColorFactor[2]), static_cast<float>(pbr.baseColorFactor[3]));
        m.baseColorTexture = textureRef(pbr.baseColorTexture, what);
        m.metallic = static_cast<float>(pbr.metallicFactor);
        m.roughness = static_cast<float>(pbr.roughnessFactor);
        m.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture, what);

        glm::vec3 emissive(0.0f);
        if (!src.emissiveFactor.empty()) {
            if (src.emissiveFactor.size() != 3) fail(what, "emissiveFactor must have 3 numbers");
            emissive = glm::vec3(static_cast<float>(src.emissiveFactor[0]), static_cast<float>(src.emissiveFactor[1]),
                                 static_cast<float>(src.emissiveFactor[2]));
        }
        const double strength =
            extensionNumber(src.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0, what);
        if (!(strength >= 0.0)) fail(what, "emissiveStrength must be >= 0");
        m.emission = emissive * static_cast<float>(strength);
        m.emissionTexture = textureRef(src.emissiveTexture, what);

        // Only the scalar factor of KHR_materials_specular; specularColor and its textures are ignored.
        m.specular =
            static_cast<float>(extensionNumber(src.extensions, "KHR_materials_specular", "specularFactor", 1.0, what));
        m.normalTexture = textureRef(src.normalTexture, what);
        m.normalScale = static_cast<float>(src.normalTexture.scale);
        m.doubleSided = src.doubleSided;
        // alphaMode (glTF 2.0 3.9.4): tinygltf leaves the string as written and alphaCutoff at 0.5 when
        // absent. BLEND has no meaning without transparency: taken as MASK at 0.5 (warned in run()).
        if (src.alphaMode == "MASK") {
            if (!(src.alphaCutoff >= 0.0)) fail(what, "alphaCutoff must be >= 0");
            m.alphaMode = Material::AlphaMode::Mask;
            m.alphaCutoff = static_cast<float>(src.alphaCutoff);
        } else if (src.alphaMode == "BLEND") {
            m.alphaMode = Material::AlphaMode::Mask;
            m.alphaCutoff = 0.5f;
        } else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty()) {
            fail(what, "alphaMode '" + src.alphaMode + "' is not OPAQUE, MASK or BLEND");
        }
        return m;
    }

    int defaultMaterial()
    {
        // vplgi's Material defaults (white dielectric, roughness 1), not glTF's (metallic 1): a
        // material-less primitive is nearly always a quick test asset, where a metal would be dark.
        if (mDefaultMaterial < 0) {
            Material m;
            m.name = "default";
            mScene.materials.push_back(m);
            mDefaultMaterial = static_cast<int>(mScene.materials.size()) - 1;
        }
        return mDefaultMaterial;
    }

    // ---- accessors ----

    AccessorView viewAccessor(int index, const std::string& what) const
    {
        if (index < 0 || static_cast<std::size_t>(index) >= mModel.accessors.size())
            fail(what, "accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& acc = mModel.accessors[static_cast<std::size_t>(index)];
        const std::string where = what + ": accessor " + std::to_string(index);

        AccessorView view;
        view.count = acc.count;
        view.componentType = acc.componentType;
        view.normalized = acc.normalized;
        switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            break;
        default:
            throw Error(mPath + ": " + where + ": componentType " + std::to_string(acc.componentType) +
                        " is not valid glTF");
        }
        switch (acc.type) {
        case TINYGLTF_TYPE_SCALAR:
            view.components = 1;
            break;
        case TINYGLTF_TYPE_VEC2:
            view.components = 2;
            break;
        case TINYGLTF_TYPE_VEC3:
            view.components = 3;
            break;
        case TINYGLTF_TYPE_VEC4:
            view.components = 4;
            break;
        default:
            throw Error(mPath + ": " + where + ": matrix accessors are not supported here");
        }
        if (acc.bufferView < 0) {
            // All zeros: only meaningful with sparse data; bounded so that a typo cannot exhaust memory.
            if (view.count > (std::size_t(1) << 24))
                throw Error(mPath + ": " + where + ": " + std::to_string(view.count) +
                            " elements without a bufferView");
            return view;
        }

        const std::vector<unsigned char>* bytes = nullptr;
        const tinygltf::BufferView& bv = bufferView(acc.bufferView, where, bytes);
        const std::vector<unsigned char>& buffer = *bytes;
        const std::size_t elementSize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(acc.componentType)) *
                                        static_cast<std::size_t>(view.components);
        view.stride = bv.byteStride == 0 ? elementSize : bv.byteStride;
        if (view.stride < elementSize)
            throw Error(mPath + ": " + where + ": byteStride " + std::to_string(view.stride) +
                        " is smaller than an element");
        const bool viewFits = bv.byteOffset <= buffer.size() && bv.byteLength <= buffer.size() - bv.byteOffset;
        bool accessorFits = viewFits && acc.byteOffset <= bv.byteLength;
        if (accessorFits && view.count > 0) {
            const std::size_t room = bv.byteLength - acc.byteOffset;
            // (count - 1) * stride + elementSize <= room, written so that it cannot overflow
            accessorFits = room >= elementSize && (view.count - 1) <= (room - elementSize) / view.stride;
        }
        if (!accessorFits) throw Error(mPath + ": " + where + ": data extends past the end of its buffer");
        view.data = buffer.data() + bv.byteOffset + acc.byteOffset;
        return view;
    }

    // The bufferView `index` and (in `buffer`) its buffer's bytes, both checked to exist.
    const tinygltf::BufferView& bufferView(int index, const std::string& where,
                                           const std::vector<unsigned char>*& buffer) const
    {
        if (index < 0 || static_cast<std::size_t>(index) >= mModel.bufferViews.size())
            throw Error(mPath + ": " + where + ": bufferView " + std::to_string(index) + " does not exist");
        const tinygltf::BufferView& bv = mModel.bufferViews[static_cast<std::size_t>(index)];
        if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= mModel.buffers.size())
            throw Error(mPath + ": " + where + ": buffer " + std::to_string(bv.buffer) + " does not exist");
        buffer = &mModel.buffers[static_cast<std::size_t>(bv.buffer)].data;
        return bv;
    }

    // A bounds-checked slice of a bufferView: `count` elements of `elementSize` bytes, tightly packed,
    // from byteOffset (sparse indices and values have no byteStride).
    const unsigned char* packedData(int index, std::size_t byteOffset, std::size_t count, std::size_t elementSize,
                                    const std::string& where) const
    {
        const std::vector<unsigned char>* bytes = nullptr;
        const tinygltf::BufferView& bv = bufferView(index, where, bytes);
        const std::vector<unsigned char>& buffer = *bytes;
        const bool fits = bv.byteOffset <= buffer.size() && bv.byteLength <= buffer.size() - bv.byteOffset &&
                          byteOffset <= bv.byteLength && count <= (bv.byteLength - byteOffset) / elementSize;
        if (!fits) throw Error(mPath + ": " + where + ": data extends past the end of its buffer");
        return buffer.data() + bv.byteOffset + byteOffset;
    }

    // Sparse substitution (glTF 2.0 section 3.6.2.3): the elements `sparse.indices` names (strictly
    // increasing, each below the accessor's count) take the tightly packed `sparse.values`, on top of
    // the bufferView's data or of zeros. Calls set(element, value bytes) for each.
    void applySparse(int accessor, const AccessorView& view,
                     const std::function<void(std::size_t, const unsigned char*)>& set) const
    {
        const tinygltf::Accessor& acc = mModel.accessors[static_cast<std::size_t>(accessor)];
        if (!acc.sparse.isSparse) return;
        const std::string where = "accessor " + std::to_string(accessor) + ": sparse";
        if (acc.sparse.count < 1 || static_cast<std::size_t>(acc.sparse.count) > view.count)
            throw Error(mPath + ": " + where + ": count " + std::to_string(acc.sparse.count) + " is not in [1, " +
                        std::to_string(view.count) + "]");
        const auto count = static_cast<std::size_t>(acc.sparse.count);
        const int indexType = acc.sparse.indices.componentType;
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw Error(mPath + ": " + where + ": indices must be unsigned 8, 16 or 32 bit integers");
        const auto indexSize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(indexType));
        const auto valueSize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(view.componentType)) *
                               static_cast<std::size_t>(view.components);
        const unsigned char* indices = packedData(acc.sparse.indices.bufferView,
                                                  static_cast<std::size_t>(std::max(0, acc.sparse.indices.byteOffset)),
                                                  count, indexSize, where + " indices");
        const unsigned char* values = packedData(acc.sparse.values.bufferView,
                                                 static_cast<std::size_t>(std::max(0, acc.sparse.values.byteOffset)),
                                                 count, valueSize, where + " values");
        std::size_t previous = 0;
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t element = readComponentAsIndex(indices + k * indexSize, indexType);
            if (element >= view.count || (k > 0 && element <= previous))
                throw Error(mPath + ": " + where + ": index " + std::to_string(element) + " (entry " +
                            std::to_string(k) + ") is not increasing and below " + std::to_string(view.count));
            set(element, values + k * valueSize);
            previous = element;
        }
    }

    // Reads count x components floats, converting integer components (normalized or not).
    std::vector<float> readFloats(int accessor, int components, const std::string& what) const
    {
        const AccessorView view = viewAccessor(accessor, what);
        if (view.components != components)
            fail(what, "accessor " + std::to_string(accessor) + " has " + std::to_string(view.components) +
                           " components, expected " + std::to_string(components));
        std::vector<float> out(view.count * static_cast<std::size_t>(components), 0.0f);
        if (view.data != nullptr)
            for (std::size_t i = 0; i < view.count; ++i)
                for (int c = 0; c < components; ++c)
                    out[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] =
                        readComponentAsFloat(view.element(i, c), view.componentType, view.normalized);
        const auto componentSize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(view.componentType));
        applySparse(accessor, view, [&](std::size_t i, const unsigned char* value) {
            for (int c = 0; c < components; ++c)
                out[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] = readComponentAsFloat(
                    value + static_cast<std::size_t>(c) * componentSize, view.componentType, view.normalized);
        });
        // Refused rather than repaired: a NaN or Inf position or normal has no sensible
        // replacement, and one such value poisons bounds, BVHs, filters and every pixel it reaches.
        for (std::size_t i = 0; i < out.size(); ++i) {
            if (std::isfinite(out[i])) continue;
            std::string value = "nan";
            if (std::isinf(out[i])) value = out[i] > 0.0f ? "inf" : "-inf";
            fail(what, "accessor " + std::to_string(accessor) + ": element " +
                           std::to_string(i / static_cast<std::size_t>(components)) + " is not finite (" + value + ")");
        }
        return out;
    }

    std::vector<std::uint32_t> readIndices(int accessor, const std::string& what) const
    {
        const AccessorView view = viewAccessor(accessor, what);
        if (view.components != 1) fail(what, "index accessor must be SCALAR");
        if (view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(what, "indices must be unsigned 8, 16 or 32 bit integers");
        std::vector<std::uint32_t> out(view.count, 0u);
        if (view.data != nullptr)
            for (std::size_t i = 0; i < view.count; ++i)
                out[i] = readComponentAsIndex(view.element(i, 0), view.componentType);
        applySparse(accessor, view,
                    [&](std::size_t i, const unsigned char* value) { out[i] = readComponentAsIndex(value, view.componentType); });
        return out;
    }

    // ---- meshes ----

    Mesh convertPrimitive(std::size_t meshIndex, std::size_t primitiveIndex)
    {
        const tinygltf::Mesh& src = mModel.meshes[meshIndex];
        const tinygltf::Primitive& prim = src.primitives[primitiveIndex];
        const std::string what = label("mesh", meshIndex, src.name) + " primitive " + std::to_string(primitiveIndex);

        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            fail(what, std::string("mode ") + modeName(mode) + " is not supported (triangles only)");

        const auto attribute = [&](const char* name) {
            auto it = prim.attributes.find(name);
            return it == prim.attributes.end() ? -1 : it->second;
        };
        const int positionAccessor = attribute("POSITION");
        if (positionAccessor < 0) fail(what, "has no POSITION attribute");

        Mesh mesh;
        mesh.name = src.name.empty() ? "mesh" + std::to_string(meshIndex) : src.name;
        if (src.primitives.size() > 1) mesh.name += "/" + std::to_string(primitiveIndex);

        const std::vector<float> positions = readFloats(positionAccessor, 3, what + ": POSITION");
        const std::size_t vertexCount = positions.size() / 3;
        mesh.vertices.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i)
            mesh.vertices[i].position = glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);

        const auto readAttribute = [&](const char* name, int components) {
            std::vector<float> values = readFloats(attribute(name), components, what + ": " + name);
            if (values.size() != vertexCount * static_cast<std::size_t>(components))
                fail(what, std::string(name) + " count differs from POSITION count");
            return values;
        };
        const bool hasNormals = attribute("NORMAL") >= 0;
        if (hasNormals) {
            const std::vector<float> n = readAttribute("NORMAL", 3);
            for (std::size_t i = 0; i < vertexCount; ++i)
                mesh.vertices[i].normal = glm::vec3(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
        }
        if (attribute("TEXCOORD_0") >= 0) {
            const std::vector<float> t = readAttribute("TEXCOORD_0", 2);
            for (std::size_t i = 0; i < vertexCount; ++i)
                mesh.vertices[i].texcoord = glm::vec2(t[2 * i], t[2 * i + 1]);
        }
        if (attribute("TEXCOORD_1") >= 0) {
            const std::vector<float> t = readAttribute("TEXCOORD_1", 2);
            for (std::size_t i = 0; i < vertexCount; ++i)
                mesh.vertices[i].texcoord1 = glm::vec2(t[2 * i], t[2 * i + 1]);
        }
        if (attribute("COLOR_0") >= 0) {
            // VEC3 or VEC4 (float, or normalized unsigned byte or short), linear (glTF 3.7.2.1).
            const int colorAccessor = attribute("COLOR_0");
            const int components = viewAccessor(colorAccessor, what + ": COLOR_0").components;
            if (components != 3 && components != 4) fail(what, "COLOR_0 must be VEC3 or VEC4");
            const std::vector<float> c = readAttribute("COLOR_0", components);
            for (std::size_t i = 0; i < vertexCount; ++i) {
                const float* p = &c[i * static_cast<std::size_t>(components)];
                mesh.vertices[i].color = glm::vec4(p[0], p[1], p[2], components == 4 ? p[3] : 1.0f);
            }
        }
        if (attribute("TANGENT") >= 0) {
            const std::vector<float> t = readAttribute("TANGENT", 4);
            for (std::size_t i = 0; i < vertexCount; ++i)
                mesh.vertices[i].tangent = glm::vec4(t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]);
            mesh.hasTangents = true;
        }

        std::vector<std::uint32_t> order;
        if (prim.indices >= 0) {
            order = readIndices(prim.indices, what + ": indices");
        } else {
            order.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i)
                order[i] = static_cast<std::uint32_t>(i);
        }
        for (std::uint32_t index : order)
            if (index >= vertexCount)
                fail(what,
                     "index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount) + " vertices)");

        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (order.size() % 3 != 0)
                fail(what, "index count " + std::to_string(order.size()) + " is not a multiple of 3");
            mesh.indices = std::move(order);
        } else {
            // glTF 2.0 spec 3.7.2.1: strip triangle i = (i, i+1+i%2, i+2-i%2); fan = (i+1, i+2, 0).
            for (std::size_t i = 0; i + 2 < order.size(); ++i) {
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                    mesh.indices.insert(mesh.indices.end(), {order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]});
                } else {
                    mesh.indices.insert(mesh.indices.end(), {order[i + 1], order[i + 2], order[0]});
                }
            }
        }

        // Degenerate triangles are dropped (counted, and warned about once per file in run()); strips
        // and fans use repeated indices on purpose to join runs, so theirs are dropped silently.
        const bool emissive = prim.material >= 0 && static_cast<std::size_t>(prim.material) < mScene.materials.size() &&
                              mScene.materials[static_cast<std::size_t>(prim.material)].isEmissive();
        const std::size_t dropped = dropDegenerateTriangles(mesh);
        if (dropped > 0 && mode == TINYGLTF_MODE_TRIANGLES) {
            if (mDroppedTriangles == 0) mFirstDropped = what;
            mDroppedTriangles += dropped;
            if (emissive) mDroppedEmissive += dropped;
            ++mDroppedPrimitives;
            if (mesh.indices.empty()) ++mEmptiedPrimitives;
        }

        if (!hasNormals) {
            // The spec asks for flat normals when NORMAL is missing: give every triangle its own
            // vertices so generateNormals' averaging stays within one face.
            std::vector<Vertex> flat;
            flat.reserve(mesh.indices.size());
            for (std::uint32_t& index : mesh.indices) {
                flat.push_back(mesh.vertices[index]);
                index = static_cast<std::uint32_t>(flat.size() - 1);
            }
            mesh.vertices = std::move(flat);
            generateNormals(mesh);
        }

        if (prim.material >= 0) {
            if (static_cast<std::size_t>(prim.material) >= mModel.materials.size())
                fail(what, "material " + std::to_string(prim.material) + " does not exist");
            mesh.material = prim.material;
        } else {
            mesh.material = defaultMaterial();
        }
        const TextureRef& normalTexture = mScene.materials[static_cast<std::size_t>(mesh.material)].normalTexture;
        if (!mesh.hasTangents && normalTexture.valid()) generateTangents(mesh, normalTexture);
        return mesh;
    }

    // Scene mesh indices for a glTF mesh, converted once and shared by every node using it.
    const std::vector<int>& sceneMeshes(int meshIndex, const std::string& what)
    {
        if (meshIndex < 0 || static_cast<std::size_t>(meshIndex) >= mModel.meshes.size())
            fail(what, "mesh " + std::to_string(meshIndex) + " does not exist");
        auto found = mMeshCache.find(meshIndex);
        if (found != mMeshCache.end()) return found->second;
        std::vector<int> indices;
        const std::size_t m = static_cast<std::size_t>(meshIndex);
        for (std::size_t p = 0; p < mModel.meshes[m].primitives.size(); ++p) {
            Mesh mesh = convertPrimitive(m, p);
            if (mesh.indices.empty()) continue; // nothing to draw (all degenerate: warned in run())
            mScene.meshes.push_back(std::move(mesh));
            indices.push_back(static_cast<int>(mScene.meshes.size()) - 1);
        }
        return mMeshCache.emplace(meshIndex, std::move(indices)).first->second;
    }

    // ---- nodes, lights, cameras ----

    glm::mat4 localTransform(const tinygltf::Node& node, const std::string& what) const
    {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(what, "matrix must have 16 numbers");
            glm::mat4 m(1.0f);
            for (int column = 0; column < 4; ++column) // glTF matrices are column-major, like glm
                for (int row = 0; row < 4; ++row)
                    m[column][row] = static_cast<float>(node.matrix[static_cast<std::size_t>(column * 4 + row)]);
            return m;
        }
        glm::mat4 translation(1.0f), rotation(1.0f), scale(1.0f);
        if (!node.translation.empty()) {
            if (node.translation.size() != 3) fail(what, "translation must have 3 numbers");
            translation[3] = glm::vec4(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                                       static_cast<float>(node.translation[2]), 1.0f);
        }
        if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) fail(what, "rotation must have 4 numbers");
            // glTF stores (x, y, z, w); glm::quat's constructor takes w first.
            glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                        static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
            if (glm::length(q) <= 0.0f) fail(what, "rotation must be a unit quaternion");
            rotation = glm::mat4_cast(glm::normalize(q));
        }
        if (!node.scale.empty()) {
            if (node.scale.size() != 3) fail(what, "scale must have 3 numbers");
            scale[0][0] = static_cast<float>(node.scale[0]);
            scale[1][1] = static_cast<float>(node.scale[1]);
            scale[2][2] = static_cast<float>(node.scale[2]);
        }
        return translation * rotation * scale;
    }

    void visitNode(int nodeIndex, const glm::mat4& parentWorld)
    {
        if (nodeIndex < 0 || static_cast<std::size_t>(nodeIndex) >= mModel.nodes.size())
            throw Error(mPath + ": node " + std::to_string(nodeIndex) + " does not exist");
        const std::size_t n = static_cast<std::size_t>(nodeIndex);
        const tinygltf::Node& node = mModel.nodes[n];
        const std::string what = label("node", n, node.name);
        if (mVisiting[n]) fail(what, "is its own ancestor (cycle in the node hierarchy)");
        // A valid glTF visits each node once; this bounds malformed DAGs that reuse subtrees.
        if (++mVisitCount > 10'000'000) fail(what, "node hierarchy is too large");
        mVisiting[n] = true;

        const glm::mat4 world = parentWorld * localTransform(node, what);
        if (node.mesh >= 0)
            for (int mesh : sceneMeshes(node.mesh, what))
                mScene.instances.push_back(Instance{mesh, world});
        if (node.camera >= 0) addCamera(node, world, what);
        auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end()) addLight(node, light->second, world, what);
        for (int child : node.children)
            visitNode(child, world);

        mVisiting[n] = false;
    }

    static glm::vec3 worldAxis(const glm::mat4& world, const glm::vec3& axis)
    {
        const glm::vec3 v = glm::mat3(world) * axis;
        const float len = glm::length(v);
        return len > 0.0f ? v / len : v;
    }

    void addLight(const tinygltf::Node& node, const tinygltf::Value& extension, const glm::mat4& world,
                  const std::string& what)
    {
        if (!extension.IsObject() || !extension.Has("light") || !extension.Get("light").IsInt())
            fail(what, "KHR_lights_punctual needs an integer \"light\"");
        const int index = extension.Get("light").GetNumberAsInt();
        if (index < 0 || static_cast<std::size_t>(index) >= mModel.lights.size())
            fail(what, "light " + std::to_string(index) + " does not exist");
        const tinygltf::Light& src = mModel.lights[static_cast<std::size_t>(index)];
        const std::string lightWhat = what + ": light " + std::to_string(index);

        Light light;
        if (src.type == "point")
            light.type = LightType::Point;
        else if (src.type == "spot")
            light.type = LightType::Spot;
        else if (src.type == "directional")
            light.type = LightType::Directional;
        else
            fail(lightWhat, "unknown type \"" + src.type + "\"");
        std::set<std::string> taken;
        for (const Light& l : mScene.lights)
            taken.insert(l.name);
        light.name =
            uniqueName(src.name.empty() ? node.name : src.name, "light" + std::to_string(mScene.lights.size()), taken);
        if (!src.color.empty()) {
            if (src.color.size() != 3) fail(lightWhat, "color must have 3 numbers");
            light.color = glm::vec3(static_cast<float>(src.color[0]), static_cast<float>(src.color[1]),
                                    static_cast<float>(src.color[2]));
        }
        light.intensity = static_cast<float>(src.intensity);
        light.range = static_cast<float>(src.range);
        light.innerConeAngle = static_cast<float>(src.spot.innerConeAngle);
        light.outerConeAngle = static_cast<float>(src.spot.outerConeAngle);
        light.position = glm::vec3(world[3]);
        light.direction = worldAxis(world, glm::vec3(0.0f, 0.0f, -1.0f));
        mScene.lights.push_back(light);
    }

    void addCamera(const tinygltf::Node& node, const glm::mat4& world, const std::string& what)
    {
        if (static_cast<std::size_t>(node.camera) >= mModel.cameras.size())
            fail(what, "camera " + std::to_string(node.camera) + " does not exist");
        const tinygltf::Camera& src = mModel.cameras[static_cast<std::size_t>(node.camera)];
        if (src.type != "perspective") return; // orthographic views have no use in this renderer
        const tinygltf::PerspectiveCamera& p = src.perspective;
        const std::string cameraWhat = what + ": camera " + std::to_string(node.camera);
        if (!(p.yfov > 0.0 && p.yfov < kPi)) fail(cameraWhat, "yfov must be in (0, pi)");
        if (!(p.znear > 0.0)) fail(cameraWhat, "znear must be > 0");
        if (p.zfar != 0.0 && !(p.zfar > p.znear)) fail(cameraWhat, "zfar must be > znear");

        Camera camera;
        std::set<std::string> taken;
        for (const Camera& c : mScene.cameras)
            taken.insert(c.name);
        camera.name = uniqueName(src.name.empty() ? node.name : src.name,
                                 "camera" + std::to_string(mScene.cameras.size()), taken);
        camera.position = glm::vec3(world[3]);
        camera.target = camera.position + worldAxis(world, glm::vec3(0.0f, 0.0f, -1.0f));
        camera.up = worldAxis(world, glm::vec3(0.0f, 1.0f, 0.0f));
        camera.fovY = static_cast<float>(p.yfov);
        camera.zNear = static_cast<float>(p.znear);
        camera.zFar = p.zfar == 0.0 ? std::max(kInfiniteFar, 1000.0f * camera.zNear) : static_cast<float>(p.zfar);
        mScene.cameras.push_back(camera);
    }

    const tinygltf::Model& mModel;
    const std::string& mPath;
    Scene& mScene;
    std::map<int, std::vector<int>> mMeshCache;
    std::vector<bool> mVisiting;
    std::size_t mVisitCount = 0;
    int mDefaultMaterial = -1;
    std::size_t mDroppedTriangles = 0;  // degenerate triangles of TRIANGLES primitives
    std::size_t mDroppedEmissive = 0;   // of those, with an emissive material
    std::size_t mDroppedPrimitives = 0; // primitives that lost at least one
    std::size_t mEmptiedPrimitives = 0; // primitives that lost all of them (not added to the scene)
    std::string mFirstDropped;          // "mesh 0 (name) primitive 0" of the first
};

// ---------------------------------------------------------------------------------------------
// Scene files
// ---------------------------------------------------------------------------------------------

using Json = nlohmann::ordered_json; // ordered: unknown keys are reported in file order

// Reads typed values out of JSON objects; every message names the file, the place and the key.
class SceneFileReader {
public:
    explicit SceneFileReader(std::string path) : mPath(std::move(path)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& message) const
    {
        throw Error(mPath + ": " + (where.empty() ? "" : where + ": ") + message);
    }

    void checkObject(const Json& value, const std::string& where) const
    {
        if (!value.is_object())
            fail(where, where.empty() ? "the top level must be a JSON object" : "must be an object");
    }

    void checkKeys(const Json& object, const std::string& where, std::initializer_list<const char*> allowed) const
    {
        checkObject(object, where);
        for (auto it = object.begin(); it != object.end(); ++it) {
            bool known = false;
            for (const char* key : allowed)
                known = known || it.key() == key;
            if (!known) fail(where, "unknown key \"" + it.key() + "\"");
        }
    }

    static const Json* find(const Json& object, const char* key)
    {
        auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    std::string string(const Json& value, const std::string& where, const char* key) const
    {
        if (!value.is_string()) fail(where, quote(key) + " must be a string");
        return value.get<std::string>();
    }

    bool boolean(const Json& value, const std::string& where, const char* key) const
    {
        if (!value.is_boolean()) fail(where, quote(key) + " must be true or false");
        return value.get<bool>();
    }

    float number(const Json& value, const std::string& where, const char* key) const
    {
        if (!value.is_number()) fail(where, quote(key) + " must be a number");
        const double v = value.get<double>();
        if (!std::isfinite(v) || std::abs(v) > 3.0e38) fail(where, quote(key) + " is out of range");
        return static_cast<float>(v);
    }

    glm::vec3 vec3(const Json& value, const std::string& where, const char* key) const
    {
        if (!value.is_array() || value.size() != 3) fail(where, quote(key) + " must be an array of 3 numbers");
        glm::vec3 v;
        for (int i = 0; i < 3; ++i) {
            const Json& c = value[static_cast<std::size_t>(i)];
            if (!c.is_number()) fail(where, quote(key) + " must be an array of 3 numbers");
            v[i] = number(c, where, key);
        }
        return v;
    }

    const Json& array(const Json& value, const std::string& where, const char* key) const
    {
        if (!value.is_array()) fail(where, quote(key) + " must be an array");
        return value;
    }

    static std::string quote(const std::string& key) { return "\"" + key + "\""; }

    const std::string& path() const { return mPath; }

private:
    std::string mPath;
};

Scene loadSource(const SceneFileReader& reader, const std::string& source)
{
    const std::string builtinPrefix = "builtin:", gltfPrefix = "gltf:";
    if (source.rfind(builtinPrefix, 0) == 0) {
        const std::string name = source.substr(builtinPrefix.size());
        if (!isBuiltinScene(name))
            reader.fail("", "\"source\": unknown built-in scene \"" + name +
                                "\" (built-in scenes: " + joinNames(builtinSceneNames()) + ")");
        return makeBuiltinScene(name);
    }
    if (source.rfind(gltfPrefix, 0) == 0) {
        fs::path file = source.substr(gltfPrefix.size());
        if (file.empty()) reader.fail("", "\"source\": empty glTF path");
        if (file.is_relative()) file = fs::path(reader.path()).parent_path() / file;
        std::error_code ec;
        if (!fs::exists(file, ec))
            reader.fail("", "\"source\": " + file.lexically_normal().string() + ": no such file");
        return loadGltf(file.lexically_normal().string());
    }
    reader.fail("", "\"source\" must start with \"builtin:\" or \"gltf:\" (got \"" + source + "\")");
}

void mergeLight(const SceneFileReader& r, Scene& scene, const Json& object, const std::string& where)
{
    r.checkKeys(
        object, where,
        {"name", "type", "position", "direction", "color", "intensity", "innerConeDeg", "outerConeDeg", "range"});
    const Json* name = SceneFileReader::find(object, "name");
    if (name == nullptr) r.fail(where, "needs a \"name\"");
    const std::string lightName = r.string(*name, where, "name");
    if (lightName.empty()) r.fail(where, "\"name\" must not be empty");

    // A light with an existing name is overridden key by key; otherwise it is a new light.
    auto existing =
        std::find_if(scene.lights.begin(), scene.lights.end(), [&](const Light& l) { return l.name == lightName; });
    Light light;
    if (existing != scene.lights.end()) {
        light = *existing;
    } else {
        light.name = lightName;
        if (SceneFileReader::find(object, "type") == nullptr) r.fail(where, "a new light needs a \"type\"");
    }

    if (const Json* v = SceneFileReader::find(object, "type")) {
        const std::string type = r.string(*v, where, "type");
        if (type == "point")
            light.type = LightType::Point;
        else if (type == "spot")
            light.type = LightType::Spot;
        else if (type == "directional")
            light.type = LightType::Directional;
        else
            r.fail(where, "\"type\" must be \"point\", \"spot\" or \"directional\" (got \"" + type + "\")");
    }
    if (const Json* v = SceneFileReader::find(object, "position")) light.position = r.vec3(*v, where, "position");
    if (const Json* v = SceneFileReader::find(object, "direction")) {
        const glm::vec3 d = r.vec3(*v, where, "direction");
        if (!(glm::length(d) > 0.0f)) r.fail(where, "\"direction\" must not be zero");
        light.direction = glm::normalize(d);
    }
    if (const Json* v = SceneFileReader::find(object, "color")) {
        light.color = r.vec3(*v, where, "color");
        if (light.color.r < 0.0f || light.color.g < 0.0f || light.color.b < 0.0f)
            r.fail(where, "\"color\" must be >= 0");
    }
    if (const Json* v = SceneFileReader::find(object, "intensity")) {
        light.intensity = r.number(*v, where, "intensity");
        if (light.intensity < 0.0f) r.fail(where, "\"intensity\" must be >= 0");
    }
    // Cone angles are written in degrees in scene files (readable) and kept in radians in Light.
    if (const Json* v = SceneFileReader::find(object, "innerConeDeg")) {
        const float deg = r.number(*v, where, "innerConeDeg");
        if (deg < 0.0f || deg > 90.0f) r.fail(where, "\"innerConeDeg\" must be in [0, 90]");
        light.innerConeAngle = deg * kPi / 180.0f;
    }
    if (const Json* v = SceneFileReader::find(object, "outerConeDeg")) {
        const float deg = r.number(*v, where, "outerConeDeg");
        if (deg <= 0.0f || deg > 90.0f) r.fail(where, "\"outerConeDeg\" must be in (0, 90]");
        light.outerConeAngle = deg * kPi / 180.0f;
    }
    if (light.type == LightType::Spot && light.innerConeAngle > light.outerConeAngle)
        r.fail(where, "\"innerConeDeg\" must be <= \"outerConeDeg\"");
    if (const Json* v = SceneFileReader::find(object, "range")) {
        light.range = r.number(*v, where, "range");
        if (light.range < 0.0f) r.fail(where, "\"range\" must be >= 0 (0 = infinite)");
    }

    if (existing != scene.lights.end())
        *existing = light;
    else
        scene.lights.push_back(light);
}

void mergeCamera(const SceneFileReader& r, Scene& scene, const Json& object, const std::string& where)
{
    r.checkKeys(object, where, {"name", "position", "target", "up", "fovYDeg", "zNear", "zFar"});
    const Json* name = SceneFileReader::find(object, "name");
    if (name == nullptr) r.fail(where, "needs a \"name\"");
    const std::string cameraName = r.string(*name, where, "name");
    if (cameraName.empty()) r.fail(where, "\"name\" must not be empty");

    // Same rule as lights: an existing name is overridden key by key.
    auto existing =
        std::find_if(scene.cameras.begin(), scene.cameras.end(), [&](const Camera& c) { return c.name == cameraName; });
    Camera camera;
    if (existing != scene.cameras.end()) {
        camera = *existing;
    } else {
        camera.name = cameraName;
        if (SceneFileReader::find(object, "position") == nullptr || SceneFileReader::find(object, "target") == nullptr)
            r.fail(where, "a new camera needs \"position\" and \"target\"");
    }
    if (const Json* v = SceneFileReader::find(object, "position")) camera.position = r.vec3(*v, where, "position");
    if (const Json* v = SceneFileReader::find(object, "target")) camera.target = r.vec3(*v, where, "target");
    if (const Json* v = SceneFileReader::find(object, "up")) camera.up = r.vec3(*v, where, "up");
    if (const Json* v = SceneFileReader::find(object, "fovYDeg")) {
        const float deg = r.number(*v, where, "fovYDeg");
        if (deg <= 0.0f || deg >= 175.0f) r.fail(where, "\"fovYDeg\" must be in (0, 175)");
        camera.fovY = deg * kPi / 180.0f;
    }
    if (const Json* v = SceneFileReader::find(object, "zNear")) camera.zNear = r.number(*v, where, "zNear");
    if (const Json* v = SceneFileReader::find(object, "zFar")) camera.zFar = r.number(*v, where, "zFar");
    if (!(camera.zNear > 0.0f && camera.zFar > camera.zNear)) r.fail(where, "need 0 < \"zNear\" < \"zFar\"");
    const glm::vec3 forward = camera.target - camera.position;
    if (!(glm::length(forward) > 0.0f)) r.fail(where, "\"position\" and \"target\" must differ");
    if (!(glm::length(camera.up) > 0.0f) ||
        glm::length(glm::cross(glm::normalize(forward), glm::normalize(camera.up))) < 1e-4f)
        r.fail(where, "\"up\" must be non-zero and not parallel to the view direction");

    if (existing != scene.cameras.end())
        *existing = camera;
    else
        scene.cameras.push_back(camera);
}

void mergeAnimation(const SceneFileReader& r, Scene& scene, const Json& object, const std::string& where)
{
    r.checkKeys(object, where, {"name", "camera", "light", "keys"});
    const Json* name = SceneFileReader::find(object, "name");
    if (name == nullptr) r.fail(where, "needs a \"name\"");
    Animation animation;
    animation.name = r.string(*name, where, "name");
    if (animation.name.empty()) r.fail(where, "\"name\" must not be empty");

    const Json* camera = SceneFileReader::find(object, "camera");
    const Json* light = SceneFileReader::find(object, "light");
    if ((camera == nullptr) == (light == nullptr)) r.fail(where, "needs exactly one of \"camera\" or \"light\"");
    // Point lights only move; everything else also needs a target (aim = target - position).
    bool needsTarget = true;
    if (camera != nullptr) {
        animation.targetKind = Animation::Target::Camera;
        animation.targetName = r.string(*camera, where, "camera");
        if (scene.findCamera(animation.targetName) == nullptr)
            r.fail(where, "no camera named \"" + animation.targetName + "\"");
    } else {
        animation.targetKind = Animation::Target::Light;
        animation.targetName = r.string(*light, where, "light");
        const Light* target = scene.findLight(animation.targetName);
        if (target == nullptr) r.fail(where, "no light named \"" + animation.targetName + "\"");
        needsTarget = target->type != LightType::Point;
    }

    const Json* keys = SceneFileReader::find(object, "keys");
    if (keys == nullptr) r.fail(where, "needs \"keys\"");
    if (r.array(*keys, where, "keys").empty()) r.fail(where, "\"keys\" must not be empty");
    for (std::size_t k = 0; k < keys->size(); ++k) {
        const std::string keyWhere = where + ".keys[" + std::to_string(k) + "]";
        const Json& key = (*keys)[k];
        r.checkKeys(key, keyWhere, {"t", "position", "target"});
        const Json* t = SceneFileReader::find(key, "t");
        const Json* position = SceneFileReader::find(key, "position");
        const Json* target = SceneFileReader::find(key, "target");
        if (t == nullptr || position == nullptr) r.fail(keyWhere, "needs \"t\" and \"position\"");
        if (needsTarget && target == nullptr) r.fail(keyWhere, "needs \"target\"");
        Keyframe frame;
        frame.time = r.number(*t, keyWhere, "t");
        if (frame.time < 0.0f) r.fail(keyWhere, "\"t\" must be >= 0");
        if (!animation.keys.empty() && !(frame.time > animation.keys.back().time))
            r.fail(keyWhere, "\"t\" must be greater than the previous key's");
        frame.position = r.vec3(*position, keyWhere, "position");
        frame.target = target != nullptr ? r.vec3(*target, keyWhere, "target") : frame.position + glm::vec3(0, -1, 0);
        animation.keys.push_back(frame);
    }

    // An animation with an existing name (from the source) is replaced.
    auto existing = std::find_if(scene.animations.begin(), scene.animations.end(),
                                 [&](const vplgi::Animation& a) { return a.name == animation.name; });
    if (existing != scene.animations.end())
        *existing = animation;
    else
        scene.animations.push_back(animation);
}

} // namespace

Scene loadGltf(const std::string& path)
{
    requireFile(path);
    const std::string ext = lowerExtension(path);
    require(ext == ".glb" || ext == ".gltf", path + ": not a .gltf or .glb file");
    return loadGltfFromMemory(readWholeFile(path), path);
}

Scene loadGltfFromMemory(const std::string& bytes, const std::string& path)
{
    const std::string ext = lowerExtension(path);
    const bool binary = ext == ".glb";
    require(binary || ext == ".gltf", path + ": not a .gltf or .glb file");
    // tinygltf takes the length as an unsigned int.
    require(bytes.size() < (std::size_t{1} << 32), path + ": larger than 4 GiB");
    std::error_code ec;
    const fs::path parent = fs::path(path).parent_path();
    const fs::path folder = fs::absolute(parent.empty() ? fs::path(".") : parent, ec);
    GltfFolder confined{fs::weakly_canonical(folder, ec)};
    checkGltfDocument(path, bytes, binary, confined.canonical);

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({gltfFileExists, gltfExpandFilePath, gltfReadWholeFile, gltfRefuseWrite, &confined});
    tinygltf::Model model;
    std::string err, warn;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned int>(bytes.size()),
                                             folder.string())
               : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                            static_cast<unsigned int>(bytes.size()), folder.string());
    // tinygltf only warns about images it could not read: treated as errors, so that a scene never
    // loads with silently missing textures.
    if (!ok || !err.empty() || !warn.empty()) {
        std::string message = firstLine(err);
        if (message.empty()) message = firstLine(warn);
        if (message.empty()) message = "tinygltf could not load the file";
        throw Error(path + ": " + message);
    }
    for (const std::string& required : model.extensionsRequired)
        if (supportedRequiredExtensions().count(required) == 0)
            throw Error(path + ": unsupported required extension " + required);

    Scene scene;
    scene.name = fs::path(path).stem().string();
    scene.source = path;
    GltfImporter(model, path, scene).run();
    if (scene.cameras.empty()) scene.cameras.push_back(makeDefaultCamera(scene.worldBounds()));
    scene.validate();
    return scene;
}

Scene loadSceneSource(const std::string& source, const std::string& sceneFilePath)
{
    return loadSource(SceneFileReader(sceneFilePath), source);
}

// Scene file keys (all optional except "source"):
//   name            string, defaults to the file stem
//   source          "builtin:<name>" or "gltf:<path>" (relative paths are relative to the file)
//   replaceLights   bool: drop the source's lights before applying "lights"
//   lights          [{name, type: point|spot|directional, position, direction, color, intensity,
//                     innerConeDeg, outerConeDeg (degrees), range}]; an existing name is
//                     overridden key by key, a new name needs "type"
//   replaceCameras  bool: drop the source's cameras before applying "cameras"
//   cameras         [{name, position, target, up, fovYDeg (degrees), zNear, zFar}]; an existing name
//                     is overridden key by key, a new one needs position and target. A camera named
//                     "default" becomes cameras[0].
//   animations      [{name, camera | light, keys: [{t, position, target}]}]; "target" may be omitted
//                     for point lights. A name that exists in the source replaces that animation.
//   technique       string, the technique this scene selects by default
//   settings        {"pass.param": number | bool | string}, stored as strings
//   normalMaps      bool, default true: false drops every material's normal map, for the renderer
//                     and the path tracer alike (a scene with and without its bumps, e.g. the glossy
//                     room's normal-mapped floor: docs/conformance.md "Normals")
//   alphaMasks      bool, default true: false makes every alpha-masked material opaque, for the
//                     renderer and the path tracer alike (scenes/cutout-solid.json)
SceneDescription loadSceneFile(const std::string& path)
{
    requireFile(path);
    return loadSceneFileFromText(readWholeFile(path), path);
}

SceneDescription loadSceneFileFromText(const std::string& text, const std::string& path,
                                       const SceneSourceLoader& sourceLoader)
{
    Json doc;
    try {
        doc = Json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throwJsonParseError(path, text, e);
    } catch (const nlohmann::json::exception& e) {
        throwJsonError(path, e);
    }

    SceneFileReader r(path);
    r.checkKeys(doc, "",
                {"name", "source", "replaceLights", "lights", "replaceCameras", "cameras", "animations", "technique",
                 "settings", "normalMaps", "alphaMasks"});

    const Json* source = SceneFileReader::find(doc, "source");
    if (source == nullptr) r.fail("", "needs a \"source\" (\"builtin:<name>\" or \"gltf:<path>\")");
    SceneDescription description;
    Scene& scene = description.scene;
    const std::string sourceText = r.string(*source, "", "source");
    scene = sourceLoader ? sourceLoader(sourceText, path) : loadSceneSource(sourceText, path);
    scene.name = fs::path(path).stem().string();
    if (const Json* v = SceneFileReader::find(doc, "name")) {
        scene.name = r.string(*v, "", "name");
        if (scene.name.empty()) r.fail("", "\"name\" must not be empty");
    }
    scene.source = path;

    if (const Json* v = SceneFileReader::find(doc, "normalMaps"))
        if (!r.boolean(*v, "", "normalMaps"))
            for (Material& m : scene.materials) m.normalTexture = {};
    if (const Json* v = SceneFileReader::find(doc, "alphaMasks"))
        if (!r.boolean(*v, "", "alphaMasks"))
            for (Material& m : scene.materials) m.alphaMode = Material::AlphaMode::Opaque;
    if (const Json* v = SceneFileReader::find(doc, "replaceLights"))
        if (r.boolean(*v, "", "replaceLights")) scene.lights.clear();
    if (const Json* v = SceneFileReader::find(doc, "lights")) {
        const Json& lights = r.array(*v, "", "lights");
        for (std::size_t i = 0; i < lights.size(); ++i)
            mergeLight(r, scene, lights[i], "lights[" + std::to_string(i) + "]");
    }

    if (const Json* v = SceneFileReader::find(doc, "replaceCameras"))
        if (r.boolean(*v, "", "replaceCameras")) scene.cameras.clear();
    if (const Json* v = SceneFileReader::find(doc, "cameras")) {
        const Json& cameras = r.array(*v, "", "cameras");
        for (std::size_t i = 0; i < cameras.size(); ++i)
            mergeCamera(r, scene, cameras[i], "cameras[" + std::to_string(i) + "]");
    }
    auto defaultCamera =
        std::find_if(scene.cameras.begin(), scene.cameras.end(), [](const Camera& c) { return c.name == "default"; });
    if (defaultCamera != scene.cameras.end()) std::rotate(scene.cameras.begin(), defaultCamera, defaultCamera + 1);
    if (scene.cameras.empty()) scene.cameras.push_back(makeDefaultCamera(scene.worldBounds()));

    if (const Json* v = SceneFileReader::find(doc, "animations")) {
        const Json& animations = r.array(*v, "", "animations");
        for (std::size_t i = 0; i < animations.size(); ++i)
            mergeAnimation(r, scene, animations[i], "animations[" + std::to_string(i) + "]");
    }

    if (const Json* v = SceneFileReader::find(doc, "technique")) description.technique = r.string(*v, "", "technique");

    if (const Json* v = SceneFileReader::find(doc, "settings")) {
        r.checkObject(*v, "settings");
        for (auto it = v->begin(); it != v->end(); ++it) {
            std::string value;
            if (it->is_string())
                value = it->get<std::string>();
            else if (it->is_boolean())
                value = it->get<bool>() ? "true" : "false";
            else if (it->is_number())
                value = it->dump(); // shortest round-trip text, "1.0" / "4096"
            else
                r.fail("settings", SceneFileReader::quote(it.key()) + " must be a number, bool or string");
            if (it.key().empty()) r.fail("settings", "keys must not be empty");
            description.settings.emplace_back(it.key(), value);
        }
    }

    scene.validate();
    return description;
}

namespace {

// A scene without light renders black, and one without triangles shows only the background: both
// are allowed (a scene being assembled, a check of cameras or geometry) but said, once, because an
// all-black image with exit status 0 looks like a renderer bug.
void warnIfEmpty(const Scene& scene)
{
    bool lit = false;
    for (const Light& light : scene.lights)
        lit = lit || glm::any(glm::greaterThan(light.radiantIntensity(), glm::vec3(0.0f)));
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
        lit =
            lit || (mesh.triangleCount() > 0 && scene.materials[static_cast<std::size_t>(mesh.material)].isEmissive());
    }
    const std::string name = scene.source.empty() ? scene.name : scene.source;
    if (scene.triangleCount() == 0) warn(name + ": the scene has no triangles");
    if (!lit)
        warn(name + ": the scene has no lights (no light with intensity > 0, no emissive surface): it renders black");
}

} // namespace

SceneDescription loadSceneSpec(const std::string& spec)
{
    SceneDescription description;
    if (isBuiltinScene(spec)) {
        description.scene = makeBuiltinScene(spec);
        return description;
    }
    const std::string ext = lowerExtension(spec);
    std::error_code ec;
    const bool exists = fs::exists(spec, ec);
    if (ext.empty() && !exists)
        throw Error("unknown scene \"" + spec + "\" (built-in scenes: " + joinNames(builtinSceneNames()) +
                    "; or a .json/.gltf/.glb path)");
    require(exists, spec + ": no such file");
    if (ext == ".json")
        description = loadSceneFile(spec);
    else if (ext == ".gltf" || ext == ".glb")
        description.scene = loadGltf(spec);
    else
        throw Error(spec + ": not a scene (expected a built-in name or a .json, .gltf or .glb file)");
    warnIfEmpty(description.scene);
    return description;
}

} // namespace vplgi
