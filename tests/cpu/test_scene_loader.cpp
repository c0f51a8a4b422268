// Scene loading: glTF files written by the tests themselves (so every expected number is known),
// scene files, the spec resolver, the repo's scenes/*.json and, when ../shared is present, the
// shared test assets.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <sys/stat.h>
#include <nlohmann/json.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_loader.h"
#include "core/util/error.h"
#include "core/util/warning.h"
#include "shared_assets.h"

#ifndef VPLGI_SOURCE_DIR
#error "VPLGI_SOURCE_DIR (the repository root) must be defined by the build"
#endif

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUByte = 5121;
constexpr int kUShort = 5123;

// A directory that exists for one test and is removed afterwards.
class TempDir {
public:
    TempDir()
    {
        std::random_device random;
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        mPath = fs::temp_directory_path() /
                ("vplgi-test-scene-loader-" + std::to_string(stamp) + "-" + std::to_string(random()));
        fs::create_directories(mPath);
    }
    ~TempDir()
    {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string file(const std::string& name) const { return (mPath / name).string(); }

private:
    fs::path mPath;
};

void writeFile(const std::string& path, const std::string& bytes)
{
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    REQUIRE(out.good());
    // scripts/gltf-validate sets VPLGI_KEEP_TEST_FILES to validate what these tests write: a copy of
    // each file, under the name of its test directory.
    if (const char* keep = std::getenv("VPLGI_KEEP_TEST_FILES")) {
        const fs::path relative = fs::relative(fs::path(path), fs::temp_directory_path());
        fs::create_directories((fs::path(keep) / relative).parent_path());
        fs::copy_file(path, fs::path(keep) / relative, fs::copy_options::overwrite_existing);
    }
}

std::string base64(const std::string& bytes)
{
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t group = static_cast<std::uint8_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) group |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) group |= static_cast<std::uint8_t>(bytes[i + 2]);
        out += kAlphabet[(group >> 18) & 63];
        out += kAlphabet[(group >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(group >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[group & 63] : '=';
    }
    return out;
}

template <typename T> std::string bytesOf(const std::vector<T>& values)
{
    std::string bytes(values.size() * sizeof(T), '\0');
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

void appendU32(std::string& out, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        out += static_cast<char>((v >> (8 * i)) & 0xFFu);
}

void appendU16(std::string& out, std::uint16_t v)
{
    out += static_cast<char>(v & 0xFFu);
    out += static_cast<char>(v >> 8);
}

// Builds a glTF document with one binary buffer, written as .gltf (data URI or .bin) or .glb.
class GltfBuilder {
public:
    json doc = {{"asset", {{"version", "2.0"}}}};

    int addView(const std::string& bytes, int byteStride = 0)
    {
        while (mBin.size() % 4 != 0)
            mBin += '\0';
        json view = {{"buffer", 0}, {"byteOffset", mBin.size()}, {"byteLength", bytes.size()}};
        if (byteStride > 0) view["byteStride"] = byteStride;
        mBin += bytes;
        return append("bufferViews", view);
    }

    int addAccessor(int view, int componentType, std::size_t count, const std::string& type, std::size_t byteOffset = 0,
                    bool normalized = false)
    {
        json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
        if (byteOffset != 0) accessor["byteOffset"] = byteOffset;
        if (normalized) accessor["normalized"] = true;
        return append("accessors", accessor);
    }

    template <typename T>
    int addData(const std::vector<T>& values, int componentType, const std::string& type, int components)
    {
        const std::size_t count = values.size() / static_cast<std::size_t>(components);
        return addAccessor(addView(bytesOf(values)), componentType, count, type);
    }

    int append(const std::string& array, const json& value)
    {
        doc[array].push_back(value);
        return static_cast<int>(doc[array].size()) - 1;
    }

    void setScene(const std::vector<int>& roots)
    {
        doc["scenes"] = json::array({{{"nodes", roots}}});
        doc["scene"] = 0;
    }

    std::string gltfWithDataUri() const
    {
        json out = doc;
        if (!mBin.empty()) // tinygltf rejects an empty data URI
            out["buffers"] = json::array(
                {{{"byteLength", mBin.size()}, {"uri", "data:application/octet-stream;base64," + base64(mBin)}}});
        return out.dump(2);
    }

    // The .gltf text; the caller writes binary() next to it as binName.
    std::string gltfWithBin(const std::string& binName) const
    {
        json out = doc;
        out["buffers"] = json::array({{{"byteLength", mBin.size()}, {"uri", binName}}});
        return out.dump(2);
    }

    const std::string& binary() const { return mBin; }

    std::string glb() const
    {
        json out = doc;
        out["buffers"] = json::array({{{"byteLength", mBin.size()}}});
        std::string text = out.dump();
        while (text.size() % 4 != 0)
            text += ' ';
        std::string bin = mBin;
        while (bin.size() % 4 != 0)
            bin += '\0';
        std::string file;
        appendU32(file, 0x46546C67u); // "glTF"
        appendU32(file, 2);
        appendU32(file, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
        appendU32(file, static_cast<std::uint32_t>(text.size()));
        appendU32(file, 0x4E4F534Au); // "JSON"
        file += text;
        appendU32(file, static_cast<std::uint32_t>(bin.size()));
        appendU32(file, 0x004E4942u); // "BIN\0"
        file += bin;
        return file;
    }

private:
    std::string mBin;
};

// A triangle (0,0,0) (1,0,0) (0,1,0) facing +z, with normals; returns the mesh index.
int addTriangleMesh(GltfBuilder& b, json primitiveExtras = json::object())
{
    const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3);
    const int normals = b.addData<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 3);
    json primitive = {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}};
    primitive.update(primitiveExtras);
    return b.append("meshes", {{"primitives", json::array({primitive})}});
}

// The message of the vplgi::Error that f throws ("<no error>" when it returns normally).
std::string errorOf(const std::function<void()>& f)
{
    try {
        f();
    } catch (const vplgi::Error& e) {
        return e.what();
    }
    return "<no error>";
}

glm::vec3 worldPosition(const vplgi::Scene& scene, std::size_t instance, std::size_t vertex)
{
    const vplgi::Instance& inst = scene.instances[instance];
    return glm::vec3(inst.worldFromObject * glm::vec4(scene.meshes[inst.mesh].vertices[vertex].position, 1.0f));
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f)
{
    return glm::length(a - b) <= tolerance;
}

const float kHalfSqrt2 = std::sqrt(0.5f);

// A 2x1 24-bit BMP: a red pixel, then a green one.
std::string twoPixelBmp()
{
    std::string bmp = "BM";
    appendU32(bmp, 62);
    appendU32(bmp, 0);
    appendU32(bmp, 54);
    appendU32(bmp, 40);
    appendU32(bmp, 2);
    appendU32(bmp, 1);
    appendU16(bmp, 1);
    appendU16(bmp, 24);
    for (std::uint32_t v : {0u, 8u, 2835u, 2835u, 0u, 0u})
        appendU32(bmp, v);
    bmp += std::string("\x00\x00\xff\x00\xff\x00\x00\x00", 8); // BGR red, BGR green, row padding
    return bmp;
}

std::uint32_t crc32(const std::string& bytes)
{
    std::uint32_t crc = 0xFFFFFFFFu;
    for (char c : bytes) {
        crc ^= static_cast<std::uint8_t>(c);
        for (int k = 0; k < 8; ++k)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void appendBigEndian32(std::string& out, std::uint32_t v)
{
    for (int i = 3; i >= 0; --i)
        out += static_cast<char>((v >> (8 * i)) & 0xFFu);
}

// A 1x1 16-bit grey + alpha PNG (grey 0xFF00, alpha 0x8080), zlib "stored" (uncompressed) data.
std::string sixteenBitPng()
{
    const std::string raw("\x00\xff\x00\x80\x80", 5); // filter byte 0, then big-endian samples
    std::uint32_t a = 1, b = 0;                       // Adler-32 of the raw data
    for (char c : raw) {
        a = (a + static_cast<std::uint8_t>(c)) % 65521u;
        b = (b + a) % 65521u;
    }
    std::string zlib("\x78\x01\x01", 3); // header, then a final stored block
    appendU16(zlib, static_cast<std::uint16_t>(raw.size()));
    appendU16(zlib, static_cast<std::uint16_t>(~raw.size()));
    zlib += raw;
    appendBigEndian32(zlib, (b << 16) | a);

    std::string png("\x89PNG\r\n\x1a\n", 8);
    const auto chunk = [&](const std::string& type, const std::string& data) {
        appendBigEndian32(png, static_cast<std::uint32_t>(data.size()));
        png += type + data;
        appendBigEndian32(png, crc32(type + data));
    };
    std::string header;
    appendBigEndian32(header, 1);
    appendBigEndian32(header, 1);
    header += std::string("\x10\x04\x00\x00\x00", 5); // 16 bits, grey + alpha, no interlace
    chunk("IHDR", header);
    chunk("IDAT", zlib);
    chunk("IEND", "");
    return png;
}

} // namespace

TEST_CASE("glTF: node TRS places a triangle in the world (interleaved data in a .bin)", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    // Interleaved position + normal (byteStride 24), u8 indices.
    const std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
    const int view = b.addView(bytesOf(interleaved), 24);
    const int positions = b.addAccessor(view, kFloat, 3, "VEC3", 0);
    const int normals = b.addAccessor(view, kFloat, 3, "VEC3", 12);
    const int indices = b.addAccessor(b.addView(std::string("\x00\x01\x02", 3)), kUByte, 3, "SCALAR");
    b.append("meshes",
             {{"primitives",
               json::array({{{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}, {"indices", indices}}})}});
    // T * R * S: scale 2, 90 degrees about +z, then translate (1,2,3).
    b.append(
        "nodes",
        {{"mesh", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, 0, kHalfSqrt2, kHalfSqrt2}}, {"scale", {2, 2, 2}}});
    b.setScene({0});
    writeFile(dir.file("tri.gltf"), b.gltfWithBin("tri.bin"));
    writeFile(dir.file("tri.bin"), b.binary());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("tri.gltf"));
    REQUIRE(scene.meshes.size() == 1);
    REQUIRE(scene.instances.size() == 1);
    CHECK(scene.triangleCount() == 1);
    CHECK(scene.name == "tri");
    CHECK(scene.source == dir.file("tri.gltf"));
    CHECK(near(worldPosition(scene, 0, 0), {1, 2, 3}));
    CHECK(near(worldPosition(scene, 0, 1), {1, 4, 3}));
    CHECK(near(worldPosition(scene, 0, 2), {-1, 2, 3}));
    CHECK(near(scene.meshes[0].vertices[1].normal, {0, 0, 1}));
    // No camera in the file: a default one is added.
    REQUIRE(scene.cameras.size() == 1);
    CHECK(scene.cameras[0].name == "default");
    // No material: the default one.
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].name == "default");
}

TEST_CASE("glTF: missing normals are generated flat (u16 indices and normalized u8 texcoords)", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    // Two triangles sharing an edge, folded: one facing +y, one facing (-1,1,-1)/sqrt(3).
    const int positions = b.addData<float>({0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1, 1}, kFloat, "VEC3", 3);
    // u8 VEC2 padded to a 4-byte stride, as glTF requires for vertex attributes.
    const std::string uv("\x00\x00\x00\x00\xff\x00\x00\x00\x00\xff\x00\x00\xff\xff\x00\x00", 16);
    const int texcoords = b.addAccessor(b.addView(uv, 4), kUByte, 4, "VEC2", 0, true);
    const int indices = b.addData<std::uint16_t>({0, 1, 2, 2, 1, 3}, kUShort, "SCALAR", 1);
    const json attributes = {{"POSITION", positions}, {"TEXCOORD_0", texcoords}};
    b.append("meshes", {{"primitives", json::array({{{"attributes", attributes}, {"indices", indices}}})}});
    b.append("nodes", {{"mesh", 0}});
    b.setScene({0});
    writeFile(dir.file("fold.gltf"), b.gltfWithDataUri());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("fold.gltf"));
    REQUIRE(scene.meshes.size() == 1);
    const vplgi::Mesh& mesh = scene.meshes[0];
    REQUIRE(mesh.triangleCount() == 2);
    const glm::vec3 expected[2] = {{0, 1, 0}, glm::normalize(glm::vec3(-1, 1, -1))};
    const glm::vec2 expectedUV[2][3] = {{{0, 0}, {1, 0}, {0, 1}}, {{0, 1}, {1, 0}, {1, 1}}};
    for (std::size_t t = 0; t < 2; ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const vplgi::Vertex& v = mesh.vertices[mesh.indices[3 * t + k]];
            INFO("triangle " << t << " corner " << k);
            CHECK(near(v.normal, expected[t]));
            CHECK(glm::length(v.texcoord - expectedUV[t][k]) < 1e-6f);
        }
    }
    CHECK_FALSE(mesh.hasTangents); // no normal map, no tangents needed
}

TEST_CASE("glTF: materials with emissive strength and specular plus textures and images", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3);
    const int normals = b.addData<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 3);
    const int texcoords = b.addData<float>({0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 2);
    json attributes = {{"POSITION", positions}, {"NORMAL", normals}, {"TEXCOORD_0", texcoords}};
    b.append("meshes", {{"name", "pair"},
                        {"primitives",
                         json::array({{{"attributes", attributes}, {"material", 0}}, {{"attributes", attributes}}})}});
    b.append("nodes", {{"mesh", 0}});
    b.setScene({0});
    b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_specular"};
    b.append("materials", {{"name", "glow"},
                           {"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.5, 0.25, 0.125, 1.0}},
                             {"baseColorTexture", {{"index", 0}}},
                             {"metallicFactor", 0.3},
                             {"roughnessFactor", 0.6}}},
                           {"normalTexture", {{"index", 1}, {"scale", 0.8}}},
                           {"emissiveFactor", {1.0, 0.5, 0.25}},
                           {"doubleSided", true},
                           {"extensions",
                            {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}},
                             {"KHR_materials_specular", {{"specularFactor", 0.5}}}}}});
    b.append("textures", {{"source", 0}});
    b.append("textures", {{"source", 1}});
    b.append("images", {{"name", "rg"}, {"uri", "data:image/bmp;base64," + base64(twoPixelBmp())}});
    // 16-bit samples must come out as 8-bit: 0xFF00 -> 254, 0x8080 -> 128.
    b.append("images", {{"name", "grey16"}, {"uri", "data:image/png;base64," + base64(sixteenBitPng())}});
    writeFile(dir.file("materials.gltf"), b.gltfWithDataUri());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("materials.gltf"));
    REQUIRE(scene.materials.size() == 2);
    const vplgi::Material& m = scene.materials[0];
    CHECK(m.name == "glow");
    CHECK(glm::length(m.baseColor - glm::vec4(0.5f, 0.25f, 0.125f, 1.0f)) < 1e-6f);
    CHECK(m.metallic == Approx(0.3f));
    CHECK(m.roughness == Approx(0.6f));
    CHECK(near(m.emission, {4.0f, 2.0f, 1.0f}));
    CHECK(m.isEmissive());
    CHECK(m.specular == Approx(0.5f));
    CHECK(m.doubleSided);
    CHECK(m.baseColorTexture.image == 0);
    CHECK(m.normalTexture.image == 1);
    CHECK(m.normalScale == Approx(0.8f));
    CHECK_FALSE(m.metallicRoughnessTexture.valid());
    CHECK(scene.materials[1].name == "default");

    REQUIRE(scene.meshes.size() == 2);
    CHECK(scene.meshes[0].name == "pair/0");
    CHECK(scene.meshes[0].material == 0);
    CHECK(scene.meshes[0].hasTangents); // normal map without TANGENT: generated
    CHECK(near(glm::vec3(scene.meshes[0].vertices[0].tangent), {1, 0, 0}));
    CHECK(scene.meshes[1].material == 1);
    CHECK_FALSE(scene.meshes[1].hasTangents);
    CHECK(scene.instances.size() == 2);

    REQUIRE(scene.images.size() == 2);
    const vplgi::Image& rg = scene.images[0];
    REQUIRE(rg.width == 2);
    REQUIRE(rg.height == 1);
    CHECK(std::vector<std::uint8_t>(rg.rgba.begin(), rg.rgba.end()) ==
          std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 255});
    const vplgi::Image& grey = scene.images[1];
    REQUIRE(grey.rgba.size() == 4);
    CHECK(std::vector<std::uint8_t>(grey.rgba.begin(), grey.rgba.end()) ==
          std::vector<std::uint8_t>{254, 254, 254, 128});
}

TEST_CASE("glTF: sparse accessors replace elements of a bufferView or of zeros, for attributes and indices",
          "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    // Positions: a bufferView with vertex 2 at (0, 1, 0), replaced by (0, 2, 0).
    const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, kFloat, "VEC3", 3);
    b.doc["accessors"][positions]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", b.addView(bytesOf(std::vector<std::uint8_t>{2, 0, 0, 0}))}, {"componentType", 5121}}},
        {"values", {{"bufferView", b.addView(bytesOf(std::vector<float>{0, 2, 0}))}}}};
    // Normals: no bufferView (zeros), every element set by sparse values in normalized bytes.
    const int normals = b.addAccessor(-1, 5120, 4, "VEC3", 0, true);
    b.doc["accessors"][normals].erase("bufferView");
    b.doc["accessors"][normals]["sparse"] = {
        {"count", 4},
        {"indices", {{"bufferView", b.addView(bytesOf(std::vector<std::uint32_t>{0, 1, 2, 3}))}, {"componentType", 5125}}},
        {"values", {{"bufferView", b.addView(bytesOf(std::vector<std::int8_t>{0, 0, 127, 0, 0, 127, 0, 0, 127, 0, 0, 127}))}}}};
    // Indices 0 1 2 0 0 0 with the second triangle made (1, 3, 2) by sparse entries 4 and 5, at a
    // byteOffset into the values' view.
    const int indices = b.addData<std::uint16_t>({0, 1, 2, 1, 0, 0}, kUShort, "SCALAR", 1);
    b.doc["accessors"][indices]["sparse"] = {
        {"count", 2},
        {"indices", {{"bufferView", b.addView(bytesOf(std::vector<std::uint16_t>{4, 5}))}, {"componentType", kUShort}}},
        {"values", {{"bufferView", b.addView(bytesOf(std::vector<std::uint16_t>{9, 3, 2}))}, {"byteOffset", 2}}}};
    b.append("meshes", {{"primitives", json::array({{{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}},
                                                     {"indices", indices}}})}});
    b.append("nodes", {{"mesh", 0}});
    const std::string path = dir.file("sparse.gltf");
    writeFile(path, b.gltfWithDataUri());
    const vplgi::Scene scene = vplgi::loadGltf(path);
    REQUIRE(scene.meshes.size() == 1);
    const vplgi::Mesh& mesh = scene.meshes[0];
    REQUIRE(mesh.vertices.size() == 4);
    CHECK(mesh.vertices[2].position == glm::vec3(0, 2, 0));
    CHECK(mesh.vertices[3].position == glm::vec3(1, 1, 0));
    for (const vplgi::Vertex& v : mesh.vertices) CHECK(near(v.normal, {0, 0, 1}));
    CHECK(mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2});
}

TEST_CASE("glTF: TEXCOORD_1, COLOR_0 and KHR_texture_transform (offset, rotation, scale, texCoord override)",
          "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3);
    const int uv0 = b.addData<float>({0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 2);
    const int uv1 = b.addData<float>({0.5f, 0.25f, 0.75f, 0.25f, 0.5f, 1}, kFloat, "VEC2", 2);
    // COLOR_0 as normalized unsigned shorts, VEC4; a second primitive has VEC3 floats.
    const int rgba = b.addData<std::uint16_t>({65535, 0, 0, 65535, 0, 65535, 0, 32768, 0, 0, 65535, 0}, kUShort,
                                              "VEC4", 4);
    b.doc["accessors"][rgba]["normalized"] = true;
    const int rgb = b.addData<float>({0.25f, 0.5f, 1, 0.25f, 0.5f, 1, 0.25f, 0.5f, 1}, kFloat, "VEC3", 3);
    b.append("meshes",
             {{"primitives",
               json::array({{{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1},
                                             {"COLOR_0", rgba}}},
                             {"material", 0}},
                            {{"attributes", {{"POSITION", positions}, {"COLOR_0", rgb}}}, {"material", 0}}})}});
    b.append("nodes", {{"mesh", 0}});
    b.setScene({0});
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    b.doc["extensionsRequired"] = {"KHR_texture_transform"};
    const json transform = {{"offset", {0, 1}}, {"rotation", 1.57079632679}, {"scale", {0.5, 0.5}}};
    b.append("materials",
             {{"name", "atlas"},
              {"pbrMetallicRoughness",
               {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}},
                {"metallicRoughnessTexture",
                 {{"index", 0}, {"texCoord", 1}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 0}}}}}}}}},
              {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
              {"emissiveFactor", {1, 1, 1}}});
    b.append("textures", {{"source", 0}});
    b.append("images", {{"name", "rg"}, {"uri", "data:image/bmp;base64," + base64(twoPixelBmp())}});
    const std::string path = dir.file("uvsets.gltf");
    writeFile(path, b.gltfWithDataUri());
    const vplgi::Scene scene = vplgi::loadGltf(path);
    REQUIRE(scene.meshes.size() == 2);
    const vplgi::Mesh& mesh = scene.meshes[0];
    CHECK(mesh.vertices[1].texcoord1 == glm::vec2(0.75f, 0.25f));
    CHECK(glm::length(mesh.vertices[0].color - glm::vec4(1, 0, 0, 1)) < 1e-6f);
    CHECK(glm::length(mesh.vertices[1].color - glm::vec4(0, 1, 0, 32768.0f / 65535.0f)) < 1e-6f);
    CHECK(glm::length(scene.meshes[1].vertices[2].color - glm::vec4(0.25f, 0.5f, 1, 1)) < 1e-6f);
    CHECK(scene.meshes[1].vertices[2].texcoord1 == glm::vec2(0.0f)); // absent: zeros
    const vplgi::Material& m = scene.materials[0];
    const vplgi::TextureRef& base = m.baseColorTexture;
    CHECK(base.texCoord == 0);
    // The extension's example: the lower left quadrant of the image (v down), rotated: (0, 0) ->
    // (0, 1), (1, 0) -> (0, 0.5), (0, 1) -> (0.5, 1), (1, 1) -> (0.5, 0.5).
    CHECK(glm::length(base.uv({0, 0}, {}) - glm::vec2(0, 1)) < 1e-6f);
    CHECK(glm::length(base.uv({1, 0}, {}) - glm::vec2(0, 0.5f)) < 1e-6f);
    CHECK(glm::length(base.uv({0, 1}, {}) - glm::vec2(0.5f, 1)) < 1e-6f);
    CHECK(glm::length(base.uv({1, 1}, {}) - glm::vec2(0.5f, 0.5f)) < 1e-6f);
    CHECK(m.metallicRoughnessTexture.texCoord == 0); // the extension's texCoord overrides
    CHECK(m.emissionTexture.texCoord == 1);
    CHECK(m.emissionTexture.uv({0.1f, 0.2f}, {0.3f, 0.4f}) == glm::vec2(0.3f, 0.4f));

    b.doc["materials"][0]["emissiveTexture"]["texCoord"] = 2;
    writeFile(path, b.gltfWithDataUri());
    CHECK(errorOf([&] { vplgi::loadGltf(path); }) ==
          path + ": material 0 (atlas): uses TEXCOORD_2 (TEXCOORD_0 and TEXCOORD_1 are supported)");
}

TEST_CASE("glTF: alphaMode MASK keeps its cutoff, BLEND becomes MASK at 0.5 with one warning, others are refused",
          "[scene_loader][alpha]")
{
    TempDir dir;
    auto build = [&](const std::vector<json>& materials) {
        GltfBuilder b;
        const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3);
        json primitives = json::array();
        for (std::size_t i = 0; i < materials.size(); ++i) {
            primitives.push_back({{"attributes", {{"POSITION", positions}}}, {"material", static_cast<int>(i)}});
            b.append("materials", materials[i]);
        }
        b.append("meshes", {{"name", "m"}, {"primitives", primitives}});
        b.append("nodes", {{"mesh", 0}});
        b.setScene({0});
        return b.gltfWithDataUri();
    };
    const std::string path = dir.file("alpha.gltf");
    writeFile(path, build({{{"name", "plain"}},
                           {{"name", "opaque"}, {"alphaMode", "OPAQUE"}, {"alphaCutoff", 0.2}},
                           {{"name", "mask"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.3}},
                           {{"name", "mask default"}, {"alphaMode", "MASK"}},
                           {{"name", "blend"}, {"alphaMode", "BLEND"}, {"alphaCutoff", 0.9}},
                           {{"name", "blend too"}, {"alphaMode", "BLEND"}}}));
    vplgi::WarningCapture warnings;
    const vplgi::Scene scene = vplgi::loadGltf(path);
    REQUIRE(scene.materials.size() == 6);
    using Mode = vplgi::Material::AlphaMode;
    CHECK(scene.materials[0].alphaMode == Mode::Opaque);
    CHECK(scene.materials[1].alphaMode == Mode::Opaque);
    CHECK(scene.materials[2].alphaMode == Mode::Mask);
    CHECK(scene.materials[2].alphaCutoff == Approx(0.3f));
    CHECK(scene.materials[3].alphaMode == Mode::Mask);
    CHECK(scene.materials[3].alphaCutoff == Approx(0.5f)); // glTF's default
    CHECK(scene.materials[4].alphaMode == Mode::Mask);
    CHECK(scene.materials[4].alphaCutoff == Approx(0.5f)); // BLEND's cutoff is ours, not the file's
    CHECK(scene.materials[5].isMasked());
    REQUIRE(warnings.messages().size() == 1);
    CHECK(warnings.messages()[0] == path + ": 2 materials with alphaMode BLEND, first material 4 (blend): drawn as "
                                           "MASK at alphaCutoff 0.5 (no transparency)");

    writeFile(path, build({{{"name", "odd"}, {"alphaMode", "mask"}}}));
    CHECK(errorOf([&] { vplgi::loadGltf(path); }) ==
          path + ": material 0 (odd): alphaMode 'mask' is not OPAQUE, MASK or BLEND");
    writeFile(path, build({{{"name", "negative"}, {"alphaMode", "MASK"}, {"alphaCutoff", -0.5}}}));
    CHECK(errorOf([&] { vplgi::loadGltf(path); }) == path + ": material 0 (negative): alphaCutoff must be >= 0");
}

TEST_CASE("glTF: KHR_lights_punctual lights take the node's world transform", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"name", "key"},
         {"type", "spot"},
         {"color", {1.0, 0.5, 0.25}},
         {"intensity", 7.0},
         {"range", 5.0},
         {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
        {{"type", "directional"}},
        {{"name", "key"}, {"type", "point"}}};
    // Parent moves by (10,0,0); the child rotates +90 degrees about x, turning -z into +y.
    b.append("nodes", {{"translation", {10, 0, 0}}, {"children", {1}}});
    b.append("nodes", {{"translation", {1, 2, 3}},
                       {"rotation", {kHalfSqrt2, 0, 0, kHalfSqrt2}},
                       {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.append("nodes", {{"name", "sunNode"}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    b.append("nodes", {{"translation", {0, 5, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    b.setScene({0, 2, 3});
    writeFile(dir.file("lights.gltf"), b.gltfWithDataUri());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("lights.gltf"));
    REQUIRE(scene.lights.size() == 3);
    const vplgi::Light& spot = scene.lights[0];
    CHECK(spot.name == "key");
    CHECK(spot.type == vplgi::LightType::Spot);
    CHECK(near(spot.position, {11, 2, 3}));
    CHECK(near(spot.direction, {0, 1, 0}));
    CHECK(near(spot.color, {1.0f, 0.5f, 0.25f}));
    CHECK(spot.intensity == Approx(7.0f));
    CHECK(spot.range == Approx(5.0f));
    CHECK(spot.innerConeAngle == Approx(0.2f));
    CHECK(spot.outerConeAngle == Approx(0.5f));

    CHECK(scene.lights[1].name == "sunNode"); // unnamed light: the node's name
    CHECK(scene.lights[1].type == vplgi::LightType::Directional);
    CHECK(near(scene.lights[1].direction, {0, 0, -1}));
    CHECK(scene.lights[2].name == "key-2"); // names are made unique
    CHECK(scene.lights[2].type == vplgi::LightType::Point);
    CHECK(near(scene.lights[2].position, {0, 5, 0}));
}

TEST_CASE("glTF: perspective camera nodes", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    b.append("cameras", {{"name", "cam"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}});
    b.append("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.2}, {"zfar", 50.0}}}});
    b.append("nodes", {{"camera", 0}, {"translation", {0, 1, 5}}});
    // +90 degrees about y turns -z into -x.
    b.append("nodes", {{"camera", 1}, {"translation", {3, 0, 0}}, {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}}});
    b.append("nodes", {{"camera", 1}, {"name", "side"}});
    b.setScene({0, 1, 2});
    writeFile(dir.file("cameras.gltf"), b.gltfWithDataUri());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("cameras.gltf"));
    REQUIRE(scene.cameras.size() == 3); // no default camera added
    const vplgi::Camera& cam = scene.cameras[0];
    CHECK(cam.name == "cam");
    CHECK(near(cam.position, {0, 1, 5}));
    CHECK(near(cam.target, {0, 1, 4}));
    CHECK(near(cam.up, {0, 1, 0}));
    CHECK(cam.fovY == Approx(0.7f));
    CHECK(cam.zNear == Approx(0.1f));
    CHECK(cam.zFar >= 1.0e4f); // infinite far plane -> a large value
    CHECK(scene.cameras[1].name == "camera1");
    CHECK(near(scene.cameras[1].target, {2, 0, 0}));
    CHECK(scene.cameras[1].zFar == Approx(50.0f));
    CHECK(scene.cameras[2].name == "side");
}

TEST_CASE("glTF binary: a mesh used by two nodes is converted once", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    addTriangleMesh(b);
    // No "scenes": every root node is loaded; node 2 is a child of node 1.
    b.append("nodes", {{"mesh", 0}, {"translation", {5, 0, 0}}});
    b.append("nodes", {{"translation", {0, 7, 0}}, {"children", {2}}});
    b.append("nodes", {{"mesh", 0}});
    writeFile(dir.file("twice.glb"), b.glb());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("twice.glb"));
    CHECK(scene.meshes.size() == 1);
    REQUIRE(scene.instances.size() == 2);
    CHECK(scene.instances[0].mesh == 0);
    CHECK(scene.instances[1].mesh == 0);
    CHECK(near(worldPosition(scene, 0, 1), {6, 0, 0}));
    CHECK(near(worldPosition(scene, 1, 1), {1, 7, 0}));
    CHECK(scene.triangleCount() == 2);
}

TEST_CASE("glTF: triangle strips and fans become lists", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    const int positions = b.addData<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, kFloat, "VEC3", 3);
    b.append("meshes", {{"primitives", json::array({{{"attributes", {{"POSITION", positions}}}, {"mode", 5}},
                                                    {{"attributes", {{"POSITION", positions}}}, {"mode", 6}}})}});
    b.append("nodes", {{"mesh", 0}});
    writeFile(dir.file("strip.gltf"), b.gltfWithDataUri());

    const vplgi::Scene scene = vplgi::loadGltf(dir.file("strip.gltf"));
    REQUIRE(scene.meshes.size() == 2);
    CHECK(scene.meshes[0].triangleCount() == 2);
    CHECK(scene.meshes[1].triangleCount() == 2);
    // Both strip triangles keep the strip's winding: normals face +z.
    for (const vplgi::Vertex& v : scene.meshes[0].vertices)
        CHECK(near(v.normal, {0, 0, 1}));
}

TEST_CASE("glTF: bad input is rejected with an Error naming the file", "[scene_loader]")
{
    TempDir dir;

    SECTION("missing file")
    {
        const std::string path = dir.file("nothing.glb");
        CHECK(errorOf([&] { vplgi::loadGltf(path); }) == path + ": no such file");
    }
    SECTION("malformed JSON")
    {
        const std::string path = dir.file("broken.gltf");
        writeFile(path, "{ \"asset\": {\"version\": \"2.0\"}, \"nodes\": [ ");
        const std::string message = errorOf([&] { vplgi::loadGltf(path); });
        CHECK_THAT(message, Contains(path + ":1:"));
        CHECK_THAT(message, Contains("invalid JSON"));
        CHECK(message.find('\n') == std::string::npos);

        // A .glb whose JSON chunk is broken.
        std::string glb = GltfBuilder().glb();
        glb.replace(20, 1, "[");
        const std::string glbPath = dir.file("broken.glb");
        writeFile(glbPath, glb);
        const std::string glbMessage = errorOf([&] { vplgi::loadGltf(glbPath); });
        CHECK_THAT(glbMessage, Contains(glbPath + ": JSON chunk:1:"));
        CHECK(glbMessage.find('\n') == std::string::npos);

        // A .glb cut short: tinygltf's message, naming the file.
        const std::string cut = dir.file("cut.glb");
        writeFile(cut, glb.substr(0, 16));
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(cut); }), Contains(cut + ": "));
    }
    SECTION("unsupported required extension, .gltf and .glb")
    {
        GltfBuilder b;
        addTriangleMesh(b);
        b.append("nodes", {{"mesh", 0}});
        b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
        b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        const std::string gltf = dir.file("draco.gltf");
        writeFile(gltf, b.gltfWithDataUri());
        CHECK(errorOf([&] { vplgi::loadGltf(gltf); }) ==
              gltf + ": unsupported required extension KHR_draco_mesh_compression");

        b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_texture_basisu"};
        b.doc["extensionsRequired"] = {"KHR_lights_punctual", "KHR_texture_basisu"};
        const std::string glb = dir.file("basisu.glb");
        writeFile(glb, b.glb());
        CHECK(errorOf([&] { vplgi::loadGltf(glb); }) == glb + ": unsupported required extension KHR_texture_basisu");
    }
    SECTION("points are not triangles")
    {
        GltfBuilder b;
        addTriangleMesh(b, {{"mode", 0}});
        b.append("nodes", {{"mesh", 0}});
        const std::string path = dir.file("points.gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }), Contains("mode POINTS is not supported"));
    }
    SECTION("sparse indices not increasing, past the count, or values past their buffer")
    {
        for (const auto& [indices, valuesOffset, message] :
             std::vector<std::tuple<std::vector<std::uint16_t>, int, std::string>>{
                 {{2, 1}, 0, "accessor 0: sparse: index 1 (entry 1) is not increasing and below 3"},
                 {{1, 3}, 0, "accessor 0: sparse: index 3 (entry 1) is not increasing and below 3"},
                 {{1, 2}, 4, "accessor 0: sparse values: data extends past the end of its buffer"}}) {
            GltfBuilder b;
            addTriangleMesh(b);
            const int indexView = b.addView(bytesOf(indices));
            const int valueView = b.addView(bytesOf(std::vector<float>{0, 2, 0, 0, 3, 0}));
            b.doc["accessors"][0]["sparse"] = {
                {"count", 2},
                {"indices", {{"bufferView", indexView}, {"componentType", kUShort}}},
                {"values", {{"bufferView", valueView}, {"byteOffset", valuesOffset}}}};
            b.append("nodes", {{"mesh", 0}});
            const std::string path = dir.file("sparse.gltf");
            writeFile(path, b.gltfWithDataUri());
            CHECK(errorOf([&] { vplgi::loadGltf(path); }) == path + ": " + message);
        }
    }
    SECTION("accessor larger than its buffer")
    {
        GltfBuilder b;
        addTriangleMesh(b);
        b.doc["accessors"][0]["count"] = 1000;
        b.append("nodes", {{"mesh", 0}});
        const std::string path = dir.file("short.gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }), Contains("past the end of its buffer"));
    }
    SECTION("index out of range")
    {
        GltfBuilder b;
        const int indices = b.addData<std::uint16_t>({0, 1, 9}, kUShort, "SCALAR", 1);
        addTriangleMesh(b, {{"indices", indices}});
        b.append("nodes", {{"mesh", 0}});
        const std::string path = dir.file("index.gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }), Contains("index 9 out of range"));
    }
    SECTION("cycle in the node hierarchy")
    {
        GltfBuilder b;
        b.append("nodes", {{"children", {1}}});
        b.append("nodes", {{"children", {0}}});
        b.setScene({0});
        const std::string path = dir.file("cycle.gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }), Contains("cycle"));
    }
    SECTION("missing external image")
    {
        GltfBuilder b;
        addTriangleMesh(b);
        b.append("nodes", {{"mesh", 0}});
        b.append("images", {{"uri", "absent.png"}});
        const std::string path = dir.file("noimage.gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }), Contains(path + ": "));
    }
}

TEST_CASE("glTF: non-finite vertex data is refused naming the accessor", "[scene_loader]")
{
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    struct Case {
        const char* name;
        std::vector<float> positions, normals;
        const char* message;
    };
    const std::vector<Case> cases = {
        {"position-nan",
         {0, 0, 0, 1, nan, 0, 0, 1, 0},
         {0, 0, 1, 0, 0, 1, 0, 0, 1},
         "mesh 0 primitive 0: POSITION: accessor 0: element 1 is not finite (nan)"},
        {"position-inf",
         {0, 0, 0, 1, 0, 0, 0, -inf, 0},
         {0, 0, 1, 0, 0, 1, 0, 0, 1},
         "mesh 0 primitive 0: POSITION: accessor 0: element 2 is not finite (-inf)"},
        {"normal-inf",
         {0, 0, 0, 1, 0, 0, 0, 1, 0},
         {inf, 0, 1, 0, 0, 1, 0, 0, 1},
         "mesh 0 primitive 0: NORMAL: accessor 1: element 0 is not finite (inf)"},
    };
    for (const Case& c : cases) {
        GltfBuilder b;
        const int positions = b.addData<float>(c.positions, kFloat, "VEC3", 3);
        const int normals = b.addData<float>(c.normals, kFloat, "VEC3", 3);
        b.append("meshes",
                 {{"primitives", json::array({{{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}}})}});
        b.append("nodes", {{"mesh", 0}});
        const std::string path = dir.file(std::string(c.name) + ".gltf");
        writeFile(path, b.gltfWithDataUri());
        CHECK(errorOf([&] { vplgi::loadGltf(path); }) == path + ": " + c.message);
    }
}

TEST_CASE("glTF: degenerate triangles are dropped with one warning that counts them", "[scene_loader]")
{
    TempDir dir;
    // Vertices 0-2: a good triangle; 3-5: collinear; 6-8: a sliver of height 1e-7 on a 1 m edge
    // (below the 1e-6 relative threshold), 9-11: a thin but honest one of height 1e-4.
    GltfBuilder b;
    const int positions = b.addData<float>({0, 0, 0, 1,    0, 0, 0,    1,     0, //
                                            0, 0, 1, 0.5f, 0, 1, 1,    0,     1, //
                                            0, 0, 2, 1,    0, 2, 0.5f, 1e-7f, 2, //
                                            0, 0, 3, 1,    0, 3, 0.5f, 1e-4f, 3},
                                           kFloat, "VEC3", 3);
    // Triangles: good, repeated index, collinear, sliver, thin.
    const int indices = b.addData<std::uint16_t>({0, 1, 2, 0, 0, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11}, kUShort, "SCALAR", 1);
    b.append("materials", {{"name", "glow"}, {"emissiveFactor", {1, 1, 1}}});
    b.append("meshes",
             {{"name", "mixed"},
              {"primitives", json::array({{{"attributes", {{"POSITION", positions}}}, {"indices", indices}}})}});
    // A second, emissive primitive with nothing but a zero-area triangle: left out of the scene.
    const int line = b.addData<float>({0, 2, 0, 1, 2, 0, 2, 2, 0}, kFloat, "VEC3", 3);
    b.append("meshes", {{"name", "lamp"},
                        {"primitives", json::array({{{"attributes", {{"POSITION", line}}}, {"material", 0}}})}});
    b.append("nodes", {{"mesh", 0}});
    b.append("nodes", {{"mesh", 1}});
    const std::string path = dir.file("degenerate.gltf");
    writeFile(path, b.gltfWithDataUri());

    vplgi::WarningCapture warnings;
    const vplgi::Scene scene = vplgi::loadGltf(path);
    REQUIRE(scene.meshes.size() == 1); // the emissive line is gone
    // The good and the thin triangle stay (re-indexed: without NORMAL every triangle gets its own
    // vertices for flat normals).
    const vplgi::Mesh& mesh = scene.meshes[0];
    REQUIRE(mesh.indices.size() == 6);
    CHECK(mesh.vertices[mesh.indices[2]].position == glm::vec3(0, 1, 0));
    CHECK(mesh.vertices[mesh.indices[5]].position == glm::vec3(0.5f, 1e-4f, 3));
    CHECK(scene.instances.size() == 1);
    REQUIRE(warnings.messages().size() == 1);
    CHECK(warnings.messages()[0] == path + ": dropped 4 degenerate (zero-area) triangles in 2 primitives, first in "
                                           "mesh 0 (mixed) primitive 0; 1 of them emissive; 1 primitive left empty");
    CHECK_NOTHROW(scene.validate());
}

TEST_CASE("glTF: external files outside the scene's folder are refused", "[scene_loader]")
{
    TempDir dir;
    writeFile(dir.file("secret.png"), twoPixelBmp()); // exists: only the folder rule can refuse it
    writeFile(dir.file("scene/inside.bmp"), twoPixelBmp());
    fs::create_directories(dir.file("scene/sub")); // "sub/.." resolves only through an existing folder
    const auto withImage = [&](const std::string& uri) {
        GltfBuilder b;
        addTriangleMesh(b);
        b.append("nodes", {{"mesh", 0}});
        b.append("images", {{"uri", uri}});
        const std::string path = dir.file("scene/image.gltf");
        writeFile(path, b.gltfWithDataUri());
        return errorOf([&] { vplgi::loadGltf(path); });
    };
    const std::string path = dir.file("scene/image.gltf");
    const std::string rule = " (refused: only data: URIs and files in the scene's folder are read)";
    CHECK(withImage("../secret.png") ==
          path + ": image 0: uri \"../secret.png\" points outside the scene's folder" + rule);
    CHECK(withImage("a/../../secret.png") ==
          path + ": image 0: uri \"a/../../secret.png\" points outside the scene's folder" + rule);
    CHECK(withImage("%2e%2E/secret.png") ==
          path + ": image 0: uri \"%2e%2E/secret.png\" points outside the scene's folder" + rule);
    CHECK(withImage("..\\secret.png") ==
          path + ": image 0: uri \"..\\secret.png\" points outside the scene's folder" + rule);
    CHECK(withImage(dir.file("secret.png")) ==
          path + ": image 0: uri \"" + dir.file("secret.png") + "\" is an absolute path" + rule);
    CHECK(withImage("file:///etc/hostname") ==
          path + ": image 0: uri \"file:///etc/hostname\" is not a relative path" + rule);
    // Inside the folder, ".." that stays inside included: loads.
    CHECK(withImage("./sub/../inside.bmp") == "<no error>");

    GltfBuilder b;
    addTriangleMesh(b);
    b.append("nodes", {{"mesh", 0}});
    writeFile(dir.file("outside.bin"), b.binary());
    const std::string bufferPath = dir.file("scene/buffer.gltf");
    writeFile(bufferPath, b.gltfWithBin("../outside.bin"));
    CHECK(errorOf([&] { vplgi::loadGltf(bufferPath); }) ==
          bufferPath + ": buffer 0: uri \"../outside.bin\" points outside the scene's folder" + rule);
}

TEST_CASE("loadSceneSpec warns about a scene without lights or triangles, and loads it", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    addTriangleMesh(b);
    b.append("nodes", {{"mesh", 0}});
    const std::string unlit = dir.file("unlit.gltf");
    writeFile(unlit, b.gltfWithDataUri());
    {
        vplgi::WarningCapture warnings;
        CHECK(vplgi::loadSceneSpec(unlit).scene.triangleCount() == 1);
        CHECK(warnings.messages() ==
              std::vector<std::string>{unlit + ": the scene has no lights (no light with intensity > 0, no emissive "
                                               "surface): it renders black"});
    }
    // A light of intensity 0 lights nothing either; one of intensity 1 does.
    const std::string file = dir.file("dark.json");
    writeFile(file, R"({"source": "gltf:unlit.gltf", "lights": [{"name": "off", "type": "point", "intensity": 0}]})");
    {
        vplgi::WarningCapture warnings;
        vplgi::loadSceneSpec(file);
        CHECK(warnings.messages().size() == 1);
    }
    writeFile(file, R"({"source": "gltf:unlit.gltf", "lights": [{"name": "on", "type": "point", "intensity": 1}]})");
    {
        vplgi::WarningCapture warnings;
        vplgi::loadSceneSpec(file);
        CHECK(warnings.messages().empty());
    }
    // No triangles at all (a glTF with only a light): two warnings, no error.
    const std::string empty = dir.file("empty.gltf");
    writeFile(empty, R"({"asset": {"version": "2.0"}})");
    {
        vplgi::WarningCapture warnings;
        CHECK(vplgi::loadSceneSpec(empty).scene.triangleCount() == 0);
        REQUIRE(warnings.messages().size() == 2);
        CHECK(warnings.messages()[0] == empty + ": the scene has no triangles");
    }
    // Built-in scenes are lit: no warning.
    {
        vplgi::WarningCapture warnings;
        vplgi::loadSceneSpec("cornell");
        CHECK(warnings.messages().empty());
    }
}

TEST_CASE("scene file: a built-in source with light and camera overrides plus animations and settings",
          "[scene_loader]")
{
    TempDir dir;
    const std::string path = dir.file("demo.json");
    writeFile(path, R"({
  "name": "furnace-demo",
  "source": "builtin:furnace",
  "lights": [
    {"name": "center", "intensity": 2.5},
    {"name": "key", "type": "spot", "position": [0, 0.5, 0], "direction": [0, -2, 0], "color": [1, 0.5, 0.25],
     "intensity": 10, "innerConeDeg": 10, "outerConeDeg": 30}
  ],
  "cameras": [
    {"name": "side", "position": [0.5, 0, 0], "target": [0, 0, 0], "fovYDeg": 45},
    {"name": "default", "position": [0, 0, 0.5], "target": [0, 0, 0], "up": [0, 1, 0], "fovYDeg": 60,
     "zNear": 0.01, "zFar": 10}
  ],
  "animations": [
    {"name": "orbit", "camera": "side", "keys": [
      {"t": 0, "position": [0.5, 0, 0], "target": [0, 0, 0]},
      {"t": 2, "position": [0, 0, 0.5], "target": [0, 0, 0]}]},
    {"name": "bob", "light": "center", "keys": [{"t": 0, "position": [0, 0, 0]}, {"t": 1, "position": [0, 0.1, 0]}]}
  ],
  "technique": "direct",
  "settings": {"renderer.exposure": 1.5, "smcir.vplCount": 4096, "filter.enabled": true, "x.mode": "fast"}
})");

    const vplgi::SceneDescription d = vplgi::loadSceneFile(path);
    const vplgi::Scene& scene = d.scene;
    CHECK(scene.name == "furnace-demo");
    CHECK(scene.source == path);
    CHECK(d.technique == "direct");
    using Setting = std::pair<std::string, std::string>;
    CHECK(d.settings == std::vector<Setting>{{"renderer.exposure", "1.5"},
                                             {"smcir.vplCount", "4096"},
                                             {"filter.enabled", "true"},
                                             {"x.mode", "fast"}});

    const vplgi::Light* center = scene.findLight("center");
    REQUIRE(center != nullptr);
    CHECK(center->intensity == Approx(2.5f));
    const vplgi::Light* key = scene.findLight("key");
    REQUIRE(key != nullptr);
    CHECK(key->type == vplgi::LightType::Spot);
    CHECK(near(key->position, {0, 0.5f, 0}));
    CHECK(near(key->direction, {0, -1, 0}));
    CHECK(near(key->color, {1, 0.5f, 0.25f}));
    CHECK(key->intensity == Approx(10.0f));
    CHECK(key->innerConeAngle == Approx(10.0 * 3.14159265358979 / 180.0));
    CHECK(key->outerConeAngle == Approx(30.0 * 3.14159265358979 / 180.0));

    REQUIRE(!scene.cameras.empty());
    CHECK(scene.cameras[0].name == "default");
    CHECK(near(scene.cameras[0].position, {0, 0, 0.5f}));
    CHECK(scene.cameras[0].fovY == Approx(60.0 * 3.14159265358979 / 180.0));
    CHECK(scene.cameras[0].zFar == Approx(10.0f));
    REQUIRE(scene.findCamera("side") != nullptr);

    REQUIRE(scene.animations.size() >= 2);
    const vplgi::Animation* orbit = nullptr;
    for (const vplgi::Animation& a : scene.animations)
        if (a.name == "orbit") orbit = &a;
    REQUIRE(orbit != nullptr);
    CHECK(orbit->targetKind == vplgi::Animation::Target::Camera);
    CHECK(orbit->duration() == Approx(2.0f));
    vplgi::Scene animated = scene;
    vplgi::applyAnimation(animated, *orbit, 1.0f);
    CHECK(near(animated.findCamera("side")->position, {0.25f, 0, 0.25f}));
}

TEST_CASE("scene file: a glTF source relative to the file with replaced lights and cameras", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    addTriangleMesh(b);
    b.append("nodes", {{"mesh", 0}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"name", "old"}, {"type", "point"}}};
    b.append("nodes", {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    writeFile(dir.file("assets/tri.gltf"), b.gltfWithDataUri());
    const std::string path = dir.file("tri-scene.json");
    writeFile(path, R"({
  "source": "gltf:assets/tri.gltf",
  "replaceLights": true,
  "lights": [{"name": "sun", "type": "directional", "direction": [0, -1, -1], "intensity": 3}],
  "replaceCameras": true,
  "cameras": [
    {"name": "side", "position": [3, 0, 0], "target": [0, 0, 0]},
    {"name": "default", "position": [0, 0, 3], "target": [0, 0, 0]}
  ],
  "animations": [{"name": "dusk", "light": "sun", "keys": [
    {"t": 0, "position": [0, 0, 0], "target": [0, -1, 0]},
    {"t": 4, "position": [0, 0, 0], "target": [1, 0, 0]}]}]
})");

    const vplgi::SceneDescription d = vplgi::loadSceneFile(path);
    const vplgi::Scene& scene = d.scene;
    CHECK(scene.name == "tri-scene");
    CHECK(scene.triangleCount() == 1);
    REQUIRE(scene.lights.size() == 1);
    CHECK(scene.lights[0].name == "sun");
    CHECK(near(scene.lights[0].direction, glm::normalize(glm::vec3(0, -1, -1))));
    REQUIRE(scene.cameras.size() == 2);
    CHECK(scene.cameras[0].name == "default"); // moved to the front
    CHECK(scene.cameras[1].name == "side");
    CHECK(d.technique.empty());
    CHECK(d.settings.empty());
    vplgi::Scene animated = scene;
    vplgi::applyAnimation(animated, animated.animations.at(0), 4.0f);
    CHECK(near(animated.lights[0].direction, {1, 0, 0}));
}

TEST_CASE("scene file: \"normalMaps\": false drops every normal map, for the renderer and the path tracer",
          "[scene_loader]")
{
    TempDir dir;
    const std::string path = dir.file("flat.json");
    const vplgi::Scene bumpy = vplgi::makeBuiltinScene("glossy");
    int mapped = 0;
    for (const vplgi::Material& m : bumpy.materials) mapped += m.normalTexture.valid() ? 1 : 0;
    REQUIRE(mapped > 0); // the glossy room's floor and block
    writeFile(path, R"({"source": "builtin:glossy", "normalMaps": false})");
    const vplgi::Scene flat = vplgi::loadSceneFile(path).scene;
    REQUIRE(flat.materials.size() == bumpy.materials.size());
    for (std::size_t i = 0; i < flat.materials.size(); ++i) {
        CHECK_FALSE(flat.materials[i].normalTexture.valid());
        CHECK(flat.materials[i].baseColorTexture.image == bumpy.materials[i].baseColorTexture.image);
    }
    writeFile(path, R"({"source": "builtin:glossy", "normalMaps": true})");
    int kept = 0;
    for (const vplgi::Material& m : vplgi::loadSceneFile(path).scene.materials) kept += m.normalTexture.valid() ? 1 : 0;
    CHECK(kept == mapped);
    writeFile(path, R"({"source": "builtin:glossy", "normalMaps": 0})");
    CHECK(errorOf([&] { vplgi::loadSceneFile(path); }) == path + ": \"normalMaps\" must be true or false");
}

TEST_CASE("scene file: \"alphaMasks\": false makes every masked material opaque (scenes/cutout-solid.json)",
          "[scene_loader][alpha]")
{
    const vplgi::Scene masked = vplgi::makeBuiltinScene("cutout");
    const vplgi::Scene solid = vplgi::loadSceneSpec(std::string(VPLGI_SOURCE_DIR) + "/scenes/cutout-solid.json").scene;
    REQUIRE(solid.materials.size() == masked.materials.size());
    int maskedCount = 0;
    for (std::size_t i = 0; i < solid.materials.size(); ++i) {
        maskedCount += masked.materials[i].isMasked() ? 1 : 0;
        CHECK_FALSE(solid.materials[i].isMasked());
        CHECK(solid.materials[i].baseColorTexture.image == masked.materials[i].baseColorTexture.image);
    }
    CHECK(maskedCount == 1);
    TempDir dir;
    const std::string path = dir.file("solid.json");
    writeFile(path, R"({"source": "builtin:cutout", "alphaMasks": "no"})");
    CHECK(errorOf([&] { vplgi::loadSceneFile(path); }) == path + ": \"alphaMasks\" must be true or false");
}

TEST_CASE("scene file: errors name the file and the key", "[scene_loader]")
{
    TempDir dir;
    const std::string path = dir.file("bad.json");
    const auto errorFor = [&](const std::string& text) {
        writeFile(path, text);
        return errorOf([&] { vplgi::loadSceneFile(path); });
    };

    CHECK(errorFor(R"({"source": "builtin:furnace", "lights": [
        {"name": "a", "type": "point"}, {"name": "b", "type": "point"},
        {"name": "c", "type": "point", "intensty": 3}]})") == path + ": lights[2]: unknown key \"intensty\"");
    CHECK(errorFor(R"({"source": "builtin:furnace", "lightz": []})") == path + ": unknown key \"lightz\"");
    CHECK(errorFor(R"({"source": "builtin:furnace", "lights": [{"name": "a", "type": "point", "intensity": -1}]})") ==
          path + ": lights[0]: \"intensity\" must be >= 0");
    CHECK(errorFor(R"({"source": "builtin:furnace", "lights": [{"name": "a", "type": "point", "intensity": "x"}]})") ==
          path + ": lights[0]: \"intensity\" must be a number");
    CHECK(errorFor(R"({"source": "builtin:furnace", "lights": [{"name": "a", "type": "area"}]})") ==
          path + ": lights[0]: \"type\" must be \"point\", \"spot\" or \"directional\" (got \"area\")");
    CHECK(errorFor(R"({"source": "builtin:furnace", "lights": [{"name": "new"}]})") ==
          path + ": lights[0]: a new light needs a \"type\"");
    CHECK(errorFor(R"({"source": "builtin:furnace",
        "cameras": [{"name": "c", "position": [0, 0, 1], "target": [0, 0]}]})") ==
          path + ": cameras[0]: \"target\" must be an array of 3 numbers");
    CHECK(errorFor(R"({"source": "builtin:nope"})") ==
          path + ": \"source\": unknown built-in scene \"nope\" (built-in scenes: board, canyon, caustics, cornell, cutout, furnace, glossy, maze, one-sided, sealed, sealed-emissive, sealed-point, sealed-spot, street)");
    CHECK(errorFor(R"({"source": "obj:x.obj"})") ==
          path + ": \"source\" must start with \"builtin:\" or \"gltf:\" (got \"obj:x.obj\")");
    CHECK(errorFor(R"({"name": "x"})") == path + ": needs a \"source\" (\"builtin:<name>\" or \"gltf:<path>\")");
    CHECK(errorFor(R"({"source": "gltf:missing.glb"})") ==
          path + ": \"source\": " + dir.file("missing.glb") + ": no such file");
    // JSON has no NaN or Inf: a number too large for a double is how a file says "not finite".
    CHECK(
        errorFor(R"({"source": "builtin:furnace", "lights": [{"name": "a", "type": "point", "intensity": 1e999}]})") ==
        path + ": invalid JSON: number overflow parsing '1e999' (numbers must be finite)");
    CHECK(errorFor(R"({"source": "builtin:furnace", "animations": [{"name": "a", "light": "ghost", "keys": []}]})") ==
          path + ": animations[0]: no light named \"ghost\"");
    CHECK(errorFor(R"({"source": "builtin:furnace", "animations": [{"name": "a", "light": "center",
        "keys": [{"t": 1, "position": [0, 0, 0]}, {"t": 1, "position": [0, 0, 0]}]}]})") ==
          path + ": animations[0].keys[1]: \"t\" must be greater than the previous key's");
    CHECK(errorFor(R"({"source": "builtin:furnace", "settings": {"a": [1]}})") ==
          path + ": settings: \"a\" must be a number, bool or string");
    CHECK(errorFor(R"([1, 2])") == path + ": the top level must be a JSON object");

    const std::string parse = errorFor("{\n  \"source\": \"builtin:cornell\",\n  oops\n}\n");
    CHECK_THAT(parse, Contains(path + ":3:3: invalid JSON: "));
    CHECK(parse.find('\n') == std::string::npos);
    CHECK(parse.find("json.exception") == std::string::npos);
}

TEST_CASE("loadSceneSpec resolves built-in names and paths", "[scene_loader]")
{
    TempDir dir;
    const vplgi::SceneDescription cornell = vplgi::loadSceneSpec("cornell");
    CHECK(cornell.scene.triangleCount() > 0);
    CHECK_FALSE(cornell.scene.cameras.empty());

    CHECK(errorOf([] { vplgi::loadSceneSpec("cornel"); }) ==
          "unknown scene \"cornel\" (built-in scenes: board, canyon, caustics, cornell, cutout, furnace, glossy, maze, one-sided, sealed, sealed-emissive, sealed-point, sealed-spot, street; or a .json/.gltf/.glb path)");
    const std::string missing = dir.file("missing.json");
    CHECK(errorOf([&] { vplgi::loadSceneSpec(missing); }) == missing + ": no such file");

    GltfBuilder b;
    addTriangleMesh(b);
    b.append("nodes", {{"mesh", 0}});
    writeFile(dir.file("tri.glb"), b.glb());
    CHECK(vplgi::loadSceneSpec(dir.file("tri.glb")).scene.triangleCount() == 1);
    writeFile(dir.file("tri.obj"), "v 0 0 0\n");
    CHECK_THAT(errorOf([&] { vplgi::loadSceneSpec(dir.file("tri.obj")); }), Contains("not a scene"));
}

TEST_CASE("scene files of the shared glTF scenes load with their lights and cameras", "[scene_loader][shared]")
{
    // scenes/shared/*.json light the ../shared glTFs as their sources do (scenes/shared/README.md);
    // they name ../shared beside the repository.
    if (!vplgi::test::findSharedAsset("scenes")) return;
    const fs::path dir = fs::path(VPLGI_SOURCE_DIR) / "scenes" / "shared";
    int loaded = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        INFO(entry.path().string());
        const vplgi::SceneDescription d = vplgi::loadSceneFile(entry.path().string());
        CHECK(d.scene.lights.size() == 1);
        REQUIRE(!d.scene.cameras.empty());
        CHECK(d.scene.cameras[0].name == "default");
        CHECK(d.scene.triangleCount() > 10);
        ++loaded;
    }
    CHECK(loaded == 4);
}

TEST_CASE("scene files of the repository load and animate", "[scene_loader]")
{
    const fs::path scenes = fs::path(VPLGI_SOURCE_DIR) / "scenes";
    std::vector<std::string> loaded;
    for (const fs::directory_entry& entry : fs::directory_iterator(scenes)) {
        if (entry.path().extension() != ".json") continue;
        INFO(entry.path().string());
        CHECK_NOTHROW(vplgi::loadSceneSpec(entry.path().string()));
        loaded.push_back(entry.path().stem().string());
    }
    for (const char* name : {"caustics", "cornell", "furnace", "glossy", "maze", "street"})
        CHECK(std::find(loaded.begin(), loaded.end(), name) != loaded.end());

    const auto findAnimation = [](const vplgi::Scene& scene, const std::string& name) -> const vplgi::Animation& {
        for (const vplgi::Animation& a : scene.animations)
            if (a.name == name) return a;
        FAIL("no animation " << name);
        throw std::logic_error("unreachable");
    };

    const vplgi::Scene maze = vplgi::loadSceneFile((scenes / "maze.json").string()).scene;
    const vplgi::Animation& lampwalk = findAnimation(maze, "lampwalk");
    vplgi::Scene start = maze, middle = maze;
    vplgi::applyAnimation(start, lampwalk, 0.0f);
    vplgi::applyAnimation(middle, lampwalk, 0.5f * lampwalk.duration());
    CHECK(glm::length(start.findLight("lamp0")->position - middle.findLight("lamp0")->position) > 0.5f);
    // The walk stays in the lamp's 6 m room: within 3 m (horizontally) of where the scene put it.
    const glm::vec3 home = maze.findLight("lamp0")->position;
    for (const vplgi::Keyframe& key : lampwalk.keys) {
        INFO("lampwalk key at t = " << key.time);
        CHECK(glm::length(glm::vec2(key.position.x - home.x, key.position.z - home.z)) < 3.0f);
    }
    CHECK(findAnimation(maze, "walk").targetKind == vplgi::Animation::Target::Camera);

    const vplgi::Scene street = vplgi::loadSceneFile((scenes / "street.json").string()).scene;
    const vplgi::Animation& sunset = findAnimation(street, "sunset");
    vplgi::Scene noon = street, dusk = street;
    vplgi::applyAnimation(noon, sunset, 0.0f);
    vplgi::applyAnimation(dusk, sunset, sunset.duration());
    const vplgi::Light* sun0 = noon.findLight("sun");
    const vplgi::Light* sun1 = dusk.findLight("sun");
    REQUIRE(sun0 != nullptr);
    CHECK(sun0->direction.y < sun1->direction.y); // the sun sinks: its light travels more horizontally
    CHECK(std::abs(glm::length(sun1->direction) - 1.0f) < 1e-5f);
}

TEST_CASE("shared test scenes load (skipped when ../shared is absent)", "[scene_loader][shared]")
{
    const std::optional<fs::path> cornellBox = vplgi::test::findSharedAsset("scenes/cornell-box/CornellBox.glb");
    if (!cornellBox) return;
    const fs::path shared = vplgi::test::sharedAssetsDir() / "scenes";
    const vplgi::Scene cornell = vplgi::loadGltf(cornellBox->string());
    CHECK(cornell.triangleCount() == 36);
    bool emissive = false;
    for (const vplgi::Material& m : cornell.materials)
        if (m.isEmissive()) {
            emissive = true;
            CHECK(m.emission.r == Approx(100.0f)); // emissiveFactor 1 x KHR_materials_emissive_strength 100
        }
    CHECK(emissive);

    int count = 0;
    for (const fs::directory_entry& folder : fs::directory_iterator(shared)) {
        if (!folder.is_directory()) continue;
        for (const fs::directory_entry& file : fs::directory_iterator(folder.path())) {
            if (file.path().extension() != ".glb") continue;
            INFO(file.path().string());
            vplgi::Scene scene;
            CHECK_NOTHROW(scene = vplgi::loadGltf(file.path().string()));
            CHECK(scene.triangleCount() > 0);
            ++count;
        }
    }
    CHECK(count >= 1);
}

TEST_CASE("a number beyond a double is invalid JSON naming the file (found by fuzzing)", "[scene_loader]")
{
    // nlohmann/json throws out_of_range (not parse_error) for it; it escaped the loaders, unnamed.
    TempDir dir;
    const std::string scene = dir.file("overflow.json");
    writeFile(scene, R"({"source": "builtin:cornell", "lights": [{"name": "a", "intensity": 1e400}]})");
    CHECK(errorOf([&] { vplgi::loadSceneFile(scene); }) == scene + ": invalid JSON: number overflow parsing '1e400' (numbers must be finite)");

    GltfBuilder b;
    b.doc["asset"]["minVersion"] = "2.0";
    std::string text = b.gltfWithDataUri();
    text.insert(text.find('{') + 1, R"("extras": -2e400,)");
    const std::string gltf = dir.file("overflow.gltf");
    writeFile(gltf, text);
    CHECK(errorOf([&] { vplgi::loadGltf(gltf); }) == gltf + ": invalid JSON: number overflow parsing '-2e400' (numbers must be finite)");
}

TEST_CASE("glTF: external buffers and images are read only from the glTF file's folder", "[scene_loader]")
{
    TempDir dir;
    GltfBuilder b;
    addTriangleMesh(b);
    b.append("nodes", {{"mesh", 0}});
    writeFile(dir.file("outside.bin"), b.binary());
    writeFile(dir.file("scene/sub/inside.bin"), b.binary());

    SECTION("a file in a subfolder loads")
    {
        const std::string path = dir.file("scene/ok.gltf");
        writeFile(path, b.gltfWithBin("sub/inside.bin"));
        CHECK(vplgi::loadGltf(path).meshes.size() == 1);
    }
    SECTION("\"../\" out of the folder is refused although the file exists")
    {
        const std::string path = dir.file("scene/up.gltf");
        writeFile(path, b.gltfWithBin("../outside.bin"));
        const std::string message = errorOf([&] { vplgi::loadGltf(path); });
        CHECK_THAT(message, Contains(path + ": "));
        CHECK_THAT(message, Contains("refused"));
    }
    SECTION("a symlink out of the folder is refused, a device file or a pipe does not hang")
    {
        fs::create_symlink(dir.file("outside.bin"), dir.file("scene/link.bin"));
        const std::string path = dir.file("scene/link.gltf");
        writeFile(path, b.gltfWithBin("link.bin"));
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(path); }),
                   Contains(path + ": buffer 0: uri \"link.bin\" points outside the scene's folder (refused"));

        // /dev/zero never ends: reading it would run out of memory.
        fs::create_symlink("/dev/zero", dir.file("scene/zero.bin"));
        const std::string zero = dir.file("scene/zero.gltf");
        writeFile(zero, b.gltfWithBin("zero.bin"));
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(zero); }),
                   Contains(zero + ": buffer 0: uri \"zero.bin\" points outside the scene's folder (refused"));

        // A named pipe inside the folder: opening it would wait for a writer forever.
        REQUIRE(mkfifo(dir.file("scene/pipe.bin").c_str(), 0600) == 0);
        const std::string pipe = dir.file("scene/pipe.gltf");
        writeFile(pipe, b.gltfWithBin("pipe.bin"));
        CHECK_THAT(errorOf([&] { vplgi::loadGltf(pipe); }),
                   Contains(pipe + ": buffer 0: uri \"pipe.bin\" is not a regular file (refused"));
    }
    SECTION("the in-memory entry points give what the files give")
    {
        const std::string path = dir.file("scene/ok.gltf");
        const std::string text = b.gltfWithBin("sub/inside.bin");
        writeFile(path, text);
        const vplgi::Scene fromFile = vplgi::loadGltf(path);
        const vplgi::Scene fromMemory = vplgi::loadGltfFromMemory(text, path);
        REQUIRE(fromMemory.meshes.size() == fromFile.meshes.size());
        CHECK(fromMemory.meshes[0].vertices.size() == fromFile.meshes[0].vertices.size());
        CHECK(fromMemory.name == fromFile.name);
        // The extension says which form the bytes are in.
        CHECK(vplgi::loadGltfFromMemory(b.glb(), dir.file("scene/any.glb")).meshes.size() == 1);
        CHECK_THAT(errorOf([&] { vplgi::loadGltfFromMemory(b.glb(), dir.file("scene/any.gltf")); }),
                   Contains("invalid JSON"));

        const std::string sceneText = R"({"source": "gltf:ok.gltf", "technique": "ir"})";
        writeFile(dir.file("scene/s.json"), sceneText);
        const vplgi::SceneDescription a = vplgi::loadSceneFile(dir.file("scene/s.json"));
        const vplgi::SceneDescription c = vplgi::loadSceneFileFromText(sceneText, dir.file("scene/s.json"));
        CHECK(c.technique == "ir");
        CHECK(c.scene.name == a.scene.name);
        CHECK(c.scene.meshes.size() == a.scene.meshes.size());
    }
}
