// The built-in scenes: generated geometry, no external assets.
//
// Every surface is built from a few primitives (grid-tessellated patches and boxes, cylinders,
// spheres) whose triangles are counter-clockwise seen from the side their analytic vertex normals
// point to. Large surfaces are tessellated so that per-vertex techniques see small triangles.
// Layouts that look random come from a seeded std::mt19937 used as `engine() % n`: the engine's
// output is fixed by the standard, distribution objects are not, so the scenes are identical
// with every standard library.
#include "core/scene/builtin_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/util/error.h"

namespace vplgi {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr double kPiDouble = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Geometry helpers

// The shape of a parametric vertex grid. A collapsed row (a sphere pole, a disc centre) holds
// copies of one point: its cells get one triangle instead of two, so no zero-area triangles appear.
struct GridShape {
    int nu;
    int nv;
    bool collapsedV0;
    bool collapsedV1;
};

// Appends the (nu+1) x (nv+1) vertices surface(u, v), u and v in [0,1], and their triangles.
// Triangles are counter-clockwise seen from the side dP/du x dP/dv points to; the surface must
// return normals on that side.
template <class Surface>
void addGrid(Mesh& mesh, const GridShape& shape, Surface surface)
{
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    const auto rowLength = static_cast<std::uint32_t>(shape.nu + 1);
    for (int j = 0; j <= shape.nv; ++j) {
        for (int i = 0; i <= shape.nu; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(shape.nu);
            const float v = static_cast<float>(j) / static_cast<float>(shape.nv);
            Vertex vertex = surface(u, v);
            vertex.texcoord = glm::vec2(u, v);
            mesh.vertices.push_back(vertex);
        }
    }
    for (int j = 0; j < shape.nv; ++j) {
        for (int i = 0; i < shape.nu; ++i) {
            // a b on row j, d c on row j + 1.
            const std::uint32_t a = base + static_cast<std::uint32_t>(j) * rowLength + static_cast<std::uint32_t>(i);
            const std::uint32_t b = a + 1, c = b + rowLength, d = a + rowLength;
            if (!(j == 0 && shape.collapsedV0)) mesh.indices.insert(mesh.indices.end(), {a, b, c});
            if (!(j == shape.nv - 1 && shape.collapsedV1)) mesh.indices.insert(mesh.indices.end(), {a, c, d});
        }
    }
}

using Quad = std::array<glm::vec3, 4>;

// A bilinear patch through q[0..3] (counter-clockwise seen from its front), nu x nv cells. The
// normal is the patch's own, so slightly non-planar measured quads still get exact normals.
void addPatch(Mesh& mesh, const Quad& q, int nu, int nv)
{
    addGrid(mesh, GridShape{nu, nv, false, false}, [&q](float u, float v) {
        Vertex vertex;
        vertex.position = glm::mix(glm::mix(q[0], q[1], u), glm::mix(q[3], q[2], u), v);
        const glm::vec3 dPdu = glm::mix(q[1] - q[0], q[2] - q[3], v);
        const glm::vec3 dPdv = glm::mix(q[3] - q[0], q[2] - q[1], u);
        vertex.normal = glm::normalize(glm::cross(dPdu, dPdv));
        return vertex;
    });
}

int cellsAlong(const glm::vec3& edge, float cellSize)
{
    // The small slack keeps 6.0 / 0.25 at 24 cells despite rounding.
    return std::max(1, static_cast<int>(std::ceil(glm::length(edge) / cellSize - 1e-3f)));
}

// The rectangle origin + s edgeU + t edgeV, s, t in [0,1], in cells of at most about cellSize;
// its front side is the one edgeU x edgeV points to. Texcoords run over [0,1] along each edge, or,
// with tileSize > 0, in units of tileSize metres (a texture then repeats every tileSize metres on
// every rectangle, whatever its size).
void addRect(Mesh& mesh, const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV, float cellSize,
             float tileSize = 0.0f)
{
    const std::size_t first = mesh.vertices.size();
    addPatch(mesh, Quad{origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV}, cellsAlong(edgeU, cellSize),
             cellsAlong(edgeV, cellSize));
    if (tileSize <= 0.0f) return;
    const glm::vec2 tiles(glm::length(edgeU) / tileSize, glm::length(edgeV) / tileSize);
    for (std::size_t i = first; i < mesh.vertices.size(); ++i) mesh.vertices[i].texcoord *= tiles;
}

// A closed axis-aligned box with outward normals. Each face gets its own vertices (sharp edges).
void addBox(Mesh& mesh, const glm::vec3& lower, const glm::vec3& upper, float cellSize, float tileSize = 0.0f)
{
    const glm::vec3 size = upper - lower;
    const glm::vec3 dx(size.x, 0.0f, 0.0f), dy(0.0f, size.y, 0.0f), dz(0.0f, 0.0f, size.z);
    addRect(mesh, glm::vec3(upper.x, lower.y, lower.z), dy, dz, cellSize, tileSize); // +x: y cross z = +x
    addRect(mesh, lower, dz, dy, cellSize, tileSize);                                // -x
    addRect(mesh, glm::vec3(lower.x, upper.y, lower.z), dz, dx, cellSize, tileSize); // +y
    addRect(mesh, lower, dx, dz, cellSize, tileSize);                                // -y
    addRect(mesh, glm::vec3(lower.x, lower.y, upper.z), dx, dy, cellSize, tileSize); // +z
    addRect(mesh, lower, dy, dx, cellSize, tileSize);                                // -z
}

// Point on the unit circle in the xz plane; as phi grows it turns from +z towards +x, so that
// d/dphi x (+y) points outwards.
glm::vec3 ringDirection(float phi)
{
    return glm::vec3(std::sin(phi), 0.0f, std::cos(phi));
}

// A vertical cylinder standing on baseCenter, optionally with top and bottom discs.
void addCylinder(Mesh& mesh, const glm::vec3& baseCenter, float radius, float height, int segments, int stacks,
                 bool caps)
{
    addGrid(mesh, GridShape{segments, stacks, false, false}, [&](float u, float v) {
        Vertex vertex;
        vertex.normal = ringDirection(2.0f * kPi * u);
        vertex.position = baseCenter + radius * vertex.normal + glm::vec3(0.0f, height * v, 0.0f);
        return vertex;
    });
    if (!caps) return;
    // The discs run from the rim (v = 0) to the centre (v = 1); turning phi backwards flips the
    // bottom disc to face down.
    for (float sense : {1.0f, -1.0f}) {
        const float y = sense > 0.0f ? height : 0.0f;
        addGrid(mesh, GridShape{segments, 1, false, true}, [&](float u, float v) {
            Vertex vertex;
            vertex.normal = glm::vec3(0.0f, sense, 0.0f);
            vertex.position = baseCenter + glm::vec3(0.0f, y, 0.0f);
            if (v < 1.0f) vertex.position += radius * (1.0f - v) * ringDirection(sense * 2.0f * kPi * u);
            return vertex;
        });
    }
}

// A UV sphere: `rings` latitude bands from the south pole (v = 0) to the north pole, `segments`
// longitude cells. Inward spheres reverse the longitude so that triangles face the inside.
void addSphere(Mesh& mesh, const glm::vec3& center, float radius, int rings, int segments, bool inward)
{
    const float sense = inward ? -1.0f : 1.0f;
    addGrid(mesh, GridShape{segments, rings, true, true}, [&](float u, float v) {
        glm::vec3 direction(0.0f, v < 0.5f ? -1.0f : 1.0f, 0.0f); // exact poles
        if (v > 0.0f && v < 1.0f) {
            const float latitude = kPi * (v - 0.5f);
            direction = std::cos(latitude) * ringDirection(sense * 2.0f * kPi * u);
            direction.y = std::sin(latitude);
        }
        Vertex vertex;
        vertex.position = center + radius * direction;
        vertex.normal = sense * direction;
        return vertex;
    });
}

// A section of a vertical cylindrical wall standing on baseCenter over the directions
// ringDirection(phi), phi in [phi0, phi1]: the inner face at `radius` (normals towards the axis), the
// outer face at radius + thickness, a flat top rim and two flat ends. No bottom: it stands on a floor.
void addRingWall(Mesh& mesh, const glm::vec3& baseCenter, float radius, float thickness, float height, float phi0,
                 float phi1, int segments)
{
    const float outer = radius + thickness;
    const glm::vec3 up(0.0f, height, 0.0f);
    // Inner face: phi runs backwards, so that dP/du x dP/dv points at the axis.
    addGrid(mesh, GridShape{segments, 1, false, false}, [&](float u, float v) {
        Vertex vertex;
        const glm::vec3 direction = ringDirection(glm::mix(phi1, phi0, u));
        vertex.normal = -direction;
        vertex.position = baseCenter + radius * direction + v * up;
        return vertex;
    });
    addGrid(mesh, GridShape{segments, 1, false, false}, [&](float u, float v) {
        Vertex vertex;
        vertex.normal = ringDirection(glm::mix(phi0, phi1, u));
        vertex.position = baseCenter + outer * vertex.normal + v * up;
        return vertex;
    });
    // Top rim: from the outer edge (v = 0) inwards, so that it faces up.
    addGrid(mesh, GridShape{segments, 1, false, false}, [&](float u, float v) {
        Vertex vertex;
        vertex.normal = glm::vec3(0.0f, 1.0f, 0.0f);
        vertex.position = baseCenter + glm::mix(outer, radius, v) * ringDirection(glm::mix(phi0, phi1, u)) + up;
        return vertex;
    });
    // The ends face away from the arc: radial x up = -d/dphi at phi0, up x radial = +d/dphi at phi1.
    const glm::vec3 start = baseCenter + radius * ringDirection(phi0), startOut = thickness * ringDirection(phi0);
    const glm::vec3 end = baseCenter + radius * ringDirection(phi1), endOut = thickness * ringDirection(phi1);
    addPatch(mesh, Quad{start, start + startOut, start + startOut + up, start + up}, 1, 1);
    addPatch(mesh, Quad{end, end + up, end + up + endOut, end + endOut}, 1, 1);
}

// ---------------------------------------------------------------------------------------------
// Procedural normal maps

// A tangent-space normal map of a periodic height field h(s, t), s, t in [0,1) over one repeat of
// the texture, h in units of that repeat's length: n = normalize(-dh/ds, -dh/dt, 1) (s along the
// tangent, t along the bitangent, i.e. texcoord x and y; rows are t, as sampleImage reads them),
// stored as 8-bit (n + 1) / 2. Central differences with wrap-around keep the map seamless, and the
// mean slope of a periodic height field is zero, so the surface keeps its mean orientation.
template <class Height>
Image makeNormalMap(const std::string& name, int size, Height height)
{
    Image image;
    image.name = name;
    image.width = image.height = size;
    image.rgba.resize(static_cast<std::size_t>(size) * size * 4);
    const float step = 1.0f / static_cast<float>(size);
    auto at = [&](int i, int j) {
        const auto wrap = [size](int k) { return ((k % size) + size) % size; };
        return height((static_cast<float>(wrap(i)) + 0.5f) * step, (static_cast<float>(wrap(j)) + 0.5f) * step);
    };
    for (int j = 0; j < size; ++j) {
        for (int i = 0; i < size; ++i) {
            const float dhds = (at(i + 1, j) - at(i - 1, j)) / (2.0f * step);
            const float dhdt = (at(i, j + 1) - at(i, j - 1)) / (2.0f * step);
            const glm::vec3 n = glm::normalize(glm::vec3(-dhds, -dhdt, 1.0f));
            std::uint8_t* texel = &image.rgba[(static_cast<std::size_t>(j) * size + i) * 4];
            for (int c = 0; c < 3; ++c)
                texel[c] = static_cast<std::uint8_t>(std::lround((0.5f * n[c] + 0.5f) * 255.0f));
            texel[3] = 255;
        }
    }
    return image;
}

float smoothStep(float edge0, float edge1, float x)
{
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// One square tile per repeat: a flat top, bevelled down into a grout line along the edges.
Image makeTileNormalMap()
{
    return makeNormalMap("tiles_normal", 128, [](float s, float t) {
        const float edge = std::min(std::min(s, 1.0f - s), std::min(t, 1.0f - t)); // distance to the grout line
        return 0.03f * smoothStep(0.02f, 0.08f, edge); // slopes up to 0.75 (37 degrees) on the bevel
    });
}

// One round bump per repeat: h = depth cos^2(pi r / (2 r0)) inside r0 of the centre.
Image makeBumpNormalMap()
{
    return makeNormalMap("bumps_normal", 128, [](float s, float t) {
        constexpr float kRadius = 0.4f, kDepth = 0.12f; // slopes up to kDepth pi / (2 kRadius) = 0.47
        const float r = glm::length(glm::vec2(s - 0.5f, t - 0.5f));
        if (r >= kRadius) return 0.0f;
        const float c = std::cos(0.5f * kPi * r / kRadius);
        return kDepth * c * c;
    });
}

// ---------------------------------------------------------------------------------------------
// Scene assembly helpers

Scene newScene(const std::string& name)
{
    Scene scene;
    scene.name = name;
    scene.source = "builtin:" + name;
    return scene;
}

// Adds a material; the defaults give a pure Lambertian surface (specular 0, see glsl/shared/brdf.h).
int addMaterial(Scene& scene, const std::string& name, const glm::vec3& albedo, float roughness = 1.0f,
                float specular = 0.0f)
{
    Material material;
    material.name = name;
    material.baseColor = glm::vec4(albedo, 1.0f);
    material.metallic = 0.0f;
    material.roughness = roughness;
    material.specular = specular;
    scene.materials.push_back(material);
    return static_cast<int>(scene.materials.size()) - 1;
}

Mesh newMesh(const std::string& name, int material)
{
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    return mesh;
}

// Moves the mesh into the scene; returns its index (for further instances).
int addMesh(Scene& scene, Mesh mesh)
{
    scene.meshes.push_back(std::move(mesh));
    return static_cast<int>(scene.meshes.size()) - 1;
}

void addInstance(Scene& scene, int mesh, const glm::mat4& worldFromObject)
{
    Instance instance;
    instance.mesh = mesh;
    instance.worldFromObject = worldFromObject;
    scene.instances.push_back(instance);
}

// A mesh used once, in place.
void placeMesh(Scene& scene, Mesh mesh)
{
    if (mesh.indices.empty()) return;
    addInstance(scene, addMesh(scene, std::move(mesh)), glm::mat4(1.0f));
}

Camera makeCamera(const std::string& name, const glm::vec3& position, const glm::vec3& target, float fovYDegrees,
                  float zNear, float zFar)
{
    Camera camera;
    camera.name = name;
    camera.position = position;
    camera.target = target;
    camera.fovY = glm::radians(fovYDegrees);
    camera.zNear = zNear;
    camera.zFar = zFar;
    return camera;
}

Light makePointLight(const std::string& name, const glm::vec3& position, const glm::vec3& color, float intensity)
{
    Light light;
    light.name = name;
    light.type = LightType::Point;
    light.position = position;
    light.color = color;
    light.intensity = intensity;
    return light;
}

// A spot light at `position` aimed at `target`; cone angles in degrees (full intensity inside the
// inner one, none outside the outer one).
Light makeSpotLight(const std::string& name, const glm::vec3& position, const glm::vec3& target,
                    const glm::vec3& color, float intensity, float innerDegrees, float outerDegrees)
{
    Light light;
    light.name = name;
    light.type = LightType::Spot;
    light.position = position;
    light.direction = glm::normalize(target - position);
    light.color = color;
    light.intensity = intensity;
    light.innerConeAngle = glm::radians(innerDegrees);
    light.outerConeAngle = glm::radians(outerDegrees);
    return light;
}

// ---------------------------------------------------------------------------------------------
// cornell

// The measured data is in millimetres with the camera at z = -800 looking along +z; turning it
// 180 degrees about y puts the camera at +z looking along -z as vplgi's cameras do.
glm::vec3 cornellToWorld(float x, float y, float z)
{
    return glm::vec3(-x, y, -z) / 1000.0f;
}

Quad cornellQuad(const std::array<float, 12>& mm)
{
    Quad quad;
    for (int i = 0; i < 4; ++i) quad[i] = cornellToWorld(mm[3 * i], mm[3 * i + 1], mm[3 * i + 2]);
    return quad;
}

// Orders the corners so the counter-clockwise side faces `towards`. The measured quads happen to be
// listed that way already; this keeps the orientation right however a face's corners are typed
// (the block sides are assembled from footprint corners here).
Quad faceTowards(Quad q, const glm::vec3& towards)
{
    const glm::vec3 normal = glm::cross(q[2] - q[0], q[3] - q[1]);
    const glm::vec3 centre = 0.25f * (q[0] + q[1] + q[2] + q[3]);
    if (glm::dot(normal, towards - centre) < 0.0f) std::swap(q[1], q[3]);
    return q;
}

// A block of the Cornell box: its top at height `top` [mm] and the four footprint corners [mm];
// faces oriented away from the block's centre. No bottom: it stands on the floor.
Mesh makeCornellBlock(const std::string& name, int material, const std::array<float, 8>& footprint, float top)
{
    Mesh mesh = newMesh(name, material);
    Quad ground, roof;
    for (int i = 0; i < 4; ++i) {
        ground[i] = cornellToWorld(footprint[2 * i], 0.0f, footprint[2 * i + 1]);
        roof[i] = cornellToWorld(footprint[2 * i], top, footprint[2 * i + 1]);
    }
    const glm::vec3 centre =
        0.125f * (ground[0] + ground[1] + ground[2] + ground[3] + roof[0] + roof[1] + roof[2] + roof[3]);
    auto addFace = [&](Quad face) {
        const glm::vec3 faceCentre = 0.25f * (face[0] + face[1] + face[2] + face[3]);
        addPatch(mesh, faceTowards(face, faceCentre + (faceCentre - centre)), 4, 4);
    };
    addFace(roof);
    for (int i = 0; i < 4; ++i) {
        const int next = (i + 1) % 4;
        addFace(Quad{ground[i], ground[next], roof[next], roof[i]});
    }
    return mesh;
}

Scene makeCornell()
{
    Scene scene = newScene("cornell");
    // RGB approximations of the measured reflectance spectra.
    const int white = addMaterial(scene, "white", glm::vec3(0.725f, 0.71f, 0.68f));
    const int red = addMaterial(scene, "red", glm::vec3(0.63f, 0.065f, 0.05f));
    const int green = addMaterial(scene, "green", glm::vec3(0.14f, 0.45f, 0.091f));
    const int light = addMaterial(scene, "light", glm::vec3(0.78f));
    scene.materials[light].emission = glm::vec3(17.0f, 12.0f, 4.0f);

    // The room's walls face its centre; measured corners in mm.
    const glm::vec3 inside = cornellToWorld(278.0f, 274.4f, 279.6f);
    constexpr int kWallCells = 8;
    auto addWall = [&](const std::string& name, int material, const std::array<float, 12>& mm) {
        Mesh mesh = newMesh(name, material);
        addPatch(mesh, faceTowards(cornellQuad(mm), inside), kWallCells, kWallCells);
        placeMesh(scene, std::move(mesh));
    };
    addWall("floor", white, {552.8f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 559.2f, 549.6f, 0.0f, 559.2f});
    addWall("ceiling", white, {556.0f, 548.8f, 0.0f, 556.0f, 548.8f, 559.2f, 0.0f, 548.8f, 559.2f, 0.0f, 548.8f, 0.0f});
    addWall("back_wall", white,
            {549.6f, 0.0f, 559.2f, 0.0f, 0.0f, 559.2f, 0.0f, 548.8f, 559.2f, 556.0f, 548.8f, 559.2f});
    addWall("green_wall", green, {0.0f, 0.0f, 559.2f, 0.0f, 0.0f, 0.0f, 0.0f, 548.8f, 0.0f, 0.0f, 548.8f, 559.2f});
    addWall("red_wall", red, {552.8f, 0.0f, 0.0f, 549.6f, 0.0f, 559.2f, 556.0f, 548.8f, 559.2f, 556.0f, 548.8f, 0.0f});

    // 0.1 mm below the ceiling so the two are not coplanar; it faces down only.
    const std::array<float, 12> lightCorners{343.0f, 548.7f, 227.0f, 343.0f, 548.7f, 332.0f,
                                             213.0f, 548.7f, 332.0f, 213.0f, 548.7f, 227.0f};
    Mesh lamp = newMesh("light", light);
    addPatch(lamp, faceTowards(cornellQuad(lightCorners), inside), 1, 1);
    placeMesh(scene, std::move(lamp));

    placeMesh(scene, makeCornellBlock("short_block", white,
                                      {130.0f, 65.0f, 82.0f, 225.0f, 240.0f, 272.0f, 290.0f, 114.0f}, 165.0f));
    placeMesh(scene, makeCornellBlock("tall_block", white,
                                      {423.0f, 247.0f, 265.0f, 296.0f, 314.0f, 456.0f, 472.0f, 406.0f}, 330.0f));

    // The classic camera: 35 mm focal length on a 25 mm film, i.e. 39.3 degrees.
    scene.cameras.push_back(makeCamera("default", cornellToWorld(278.0f, 273.0f, -800.0f),
                                       cornellToWorld(278.0f, 273.0f, 279.6f), 39.3f, 0.01f, 10.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// maze

constexpr int kMazeColumns = 5;            // cells along x
constexpr int kMazeRows = 4;               // cells along z
constexpr float kMazeCell = 6.0f;          // [m]
constexpr float kMazeHeight = 3.0f;        // floor to ceiling [m]
constexpr float kMazeWall = 0.2f;          // wall thickness [m]
constexpr float kMazeTessellation = 0.25f; // quad size on walls, floor and ceiling [m]
constexpr float kDoorWidth = 1.2f;
constexpr float kDoorHeight = 2.2f;
constexpr std::uint32_t kMazeSeed = 20240607u;

// A perfect maze (a spanning tree of the cell grid): every room reaches every other through
// exactly one path, so most rooms are hidden from each other. Each passage is a doorway.
struct MazeLayout {
    // Passage between (c, r) and (c + 1, r), resp. (c, r + 1); the door centre is `offset`
    // metres along the wall from the cell's corner with lower coordinates.
    std::vector<std::optional<float>> eastDoor;
    std::vector<std::optional<float>> southDoor;
};

int mazeCell(int column, int row)
{
    return row * kMazeColumns + column;
}

glm::vec3 mazeCellOrigin(int column, int row)
{
    // The maze is centred on the origin.
    return glm::vec3(column * kMazeCell - 0.5f * kMazeColumns * kMazeCell, 0.0f,
                     row * kMazeCell - 0.5f * kMazeRows * kMazeCell);
}

MazeLayout makeMazeLayout(std::mt19937& engine)
{
    MazeLayout layout;
    layout.eastDoor.resize(kMazeColumns * kMazeRows);
    layout.southDoor.resize(kMazeColumns * kMazeRows);
    std::vector<bool> visited(kMazeColumns * kMazeRows, false);
    // Depth-first search with an explicit stack (the "recursive backtracker").
    std::vector<std::pair<int, int>> stack{{0, 0}};
    visited[0] = true;
    while (!stack.empty()) {
        const auto [column, row] = stack.back();
        std::vector<std::pair<int, int>> next;
        const std::array<std::pair<int, int>, 4> steps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
        for (const auto& [dc, dr] : steps) {
            const int c = column + dc, r = row + dr;
            if (c >= 0 && c < kMazeColumns && r >= 0 && r < kMazeRows && !visited[mazeCell(c, r)])
                next.emplace_back(c, r);
        }
        if (next.empty()) {
            stack.pop_back();
            continue;
        }
        const auto [c, r] = next[engine() % next.size()];
        // Doors between 2.0 and 4.0 m along the 6 m wall keep the corners free for furniture.
        const float offset = 2.0f + 0.1f * static_cast<float>(engine() % 21);
        if (r == row)
            layout.eastDoor[mazeCell(std::min(c, column), row)] = offset;
        else
            layout.southDoor[mazeCell(column, std::min(r, row))] = offset;
        visited[mazeCell(c, r)] = true;
        stack.emplace_back(c, r);
    }
    return layout;
}

// A wall of thickness kMazeWall centred on the line x = across (alongX false) or z = across
// (alongX true), from `from` to `to` along it, with an optional doorway centred at `door`
// (absolute coordinate). Solid boxes, so no light leaks through seams.
void addMazeWall(Mesh& mesh, bool alongX, float across, float from, float to, std::optional<float> door)
{
    auto box = [&](float a0, float a1, float y0, float y1) {
        const float half = 0.5f * kMazeWall;
        const glm::vec3 lower = alongX ? glm::vec3(a0, y0, across - half) : glm::vec3(across - half, y0, a0);
        const glm::vec3 upper = alongX ? glm::vec3(a1, y1, across + half) : glm::vec3(across + half, y1, a1);
        addBox(mesh, lower, upper, kMazeTessellation);
    };
    if (!door) {
        box(from, to, 0.0f, kMazeHeight);
        return;
    }
    const float left = *door - 0.5f * kDoorWidth, right = *door + 0.5f * kDoorWidth;
    box(from, left, 0.0f, kMazeHeight);
    box(right, to, 0.0f, kMazeHeight);
    box(left, right, kDoorHeight, kMazeHeight); // lintel
}

// Walls on the x = const lines run the full cell length (and past the maze's ends by half a
// wall); walls on z = const lines stop at their faces, so no two boxes overlap.
void addMazeWalls(const MazeLayout& layout, Mesh& outer, Mesh& alongZ, Mesh& alongX)
{
    const float half = 0.5f * kMazeWall;
    for (int line = 0; line <= kMazeColumns; ++line) {
        for (int row = 0; row < kMazeRows; ++row) {
            const glm::vec3 corner = mazeCellOrigin(line, row);
            const float from = corner.z - (row == 0 ? half : 0.0f);
            const float to = corner.z + kMazeCell + (row == kMazeRows - 1 ? half : 0.0f);
            const bool boundary = line == 0 || line == kMazeColumns;
            std::optional<float> door;
            if (!boundary) {
                if (const auto offset = layout.eastDoor[mazeCell(line - 1, row)]) door = corner.z + *offset;
            }
            addMazeWall(boundary ? outer : alongZ, false, corner.x, from, to, door);
        }
    }
    for (int line = 0; line <= kMazeRows; ++line) {
        for (int column = 0; column < kMazeColumns; ++column) {
            const glm::vec3 corner = mazeCellOrigin(column, line);
            const bool boundary = line == 0 || line == kMazeRows;
            std::optional<float> door;
            if (!boundary) {
                if (const auto offset = layout.southDoor[mazeCell(column, line - 1)]) door = corner.x + *offset;
            }
            addMazeWall(boundary ? outer : alongX, true, corner.z, corner.x + half, corner.x + kMazeCell - half, door);
        }
    }
}

// A point `inset` metres from the walls in corner `corner` (bit 0: high x, bit 1: high z) of a cell.
glm::vec3 mazeCorner(int column, int row, int corner, float inset)
{
    const float x = (corner & 1) ? kMazeCell - inset : inset;
    const float z = (corner & 2) ? kMazeCell - inset : inset;
    return mazeCellOrigin(column, row) + glm::vec3(x, 0.0f, z);
}

// Furniture: one mesh each in object space, placed by instances. Corners of a room: columns on
// one diagonal, a pedestal with a glossy sphere and a turned crate on the other. Doors are 2-4 m
// along the walls, so none of this blocks a doorway or the line of sight straight through it.
void addMazeFurniture(Scene& scene, std::mt19937& engine, int stone, int glossy, int wood)
{
    Mesh column = newMesh("column", stone);
    addCylinder(column, glm::vec3(0.0f), 0.25f, kMazeHeight, 64, 12, false); // floor to ceiling: no caps
    Mesh glossyColumn = column;
    glossyColumn.name = "column_glossy";
    glossyColumn.material = glossy;
    Mesh pedestal = newMesh("pedestal", stone);
    addBox(pedestal, glm::vec3(-0.3f, 0.0f, -0.3f), glm::vec3(0.3f, 1.0f, 0.3f), 0.1f);
    Mesh sphere = newMesh("sphere", glossy);
    addSphere(sphere, glm::vec3(0.0f, 1.35f, 0.0f), 0.35f, 24, 48, false);
    Mesh crate = newMesh("crate", wood);
    addBox(crate, glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 0.8f, 0.4f), 0.1f);

    const int columnMesh = addMesh(scene, std::move(column));
    const int glossyColumnMesh = addMesh(scene, std::move(glossyColumn));
    const int pedestalMesh = addMesh(scene, std::move(pedestal));
    const int sphereMesh = addMesh(scene, std::move(sphere));
    const int crateMesh = addMesh(scene, std::move(crate));
    auto at = [](const glm::vec3& position) { return glm::translate(glm::mat4(1.0f), position); };
    for (int row = 0; row < kMazeRows; ++row) {
        for (int c = 0; c < kMazeColumns; ++c) {
            const int corner = static_cast<int>(engine() % 4);
            for (int k : {corner, corner ^ 3}) {
                const int mesh = engine() % 3 == 0 ? glossyColumnMesh : columnMesh;
                addInstance(scene, mesh, at(mazeCorner(c, row, k, 0.8f)));
            }
            const glm::mat4 pedestalAt = at(mazeCorner(c, row, corner ^ 1, 1.5f));
            addInstance(scene, pedestalMesh, pedestalAt);
            addInstance(scene, sphereMesh, pedestalAt);
            const float angle = glm::radians(static_cast<float>(engine() % 90));
            addInstance(scene, crateMesh,
                        glm::rotate(at(mazeCorner(c, row, corner ^ 2, 1.4f)), angle, glm::vec3(0.0f, 1.0f, 0.0f)));
        }
    }
}

struct MazeLamp {
    int column;
    int row;
    float intensity; // [W/sr]
    glm::vec3 color;
};

// Lamps in 8 of the 20 rooms, spread over the maze; the other rooms are lit only indirectly.
const std::array<MazeLamp, 8> kMazeLamps{{
    {0, 0, 30.0f, {1.0f, 0.78f, 0.55f}},
    {2, 0, 25.0f, {0.65f, 0.8f, 1.0f}},
    {4, 1, 35.0f, {1.0f, 0.85f, 0.65f}},
    {1, 2, 20.0f, {1.0f, 0.75f, 0.5f}},
    {3, 2, 40.0f, {0.7f, 0.85f, 1.0f}},
    {0, 3, 25.0f, {1.0f, 0.9f, 0.75f}},
    {2, 3, 30.0f, {0.75f, 0.9f, 1.0f}},
    {4, 3, 35.0f, {1.0f, 0.8f, 0.6f}},
}};

constexpr float kLampHeight = 2.6f;

bool mazeCellIsLit(int column, int row)
{
    return std::any_of(kMazeLamps.begin(), kMazeLamps.end(),
                       [&](const MazeLamp& lamp) { return lamp.column == column && lamp.row == row; });
}

// A doorway seen from one of its two rooms.
struct MazeDoor {
    glm::vec3 centre;  // on the floor, in the middle of the wall
    glm::vec3 through; // unit direction from this room into the next
    int nextColumn;
    int nextRow;
};

// The doorways of a cell, in the order east, west, south, north.
std::vector<MazeDoor> mazeDoors(const MazeLayout& layout, int column, int row)
{
    std::vector<MazeDoor> doors;
    const glm::vec3 origin = mazeCellOrigin(column, row);
    if (column + 1 < kMazeColumns) {
        if (const auto offset = layout.eastDoor[mazeCell(column, row)])
            doors.push_back({origin + glm::vec3(kMazeCell, 0.0f, *offset), {1.0f, 0.0f, 0.0f}, column + 1, row});
    }
    if (column > 0) {
        if (const auto offset = layout.eastDoor[mazeCell(column - 1, row)])
            doors.push_back({origin + glm::vec3(0.0f, 0.0f, *offset), {-1.0f, 0.0f, 0.0f}, column - 1, row});
    }
    if (row + 1 < kMazeRows) {
        if (const auto offset = layout.southDoor[mazeCell(column, row)])
            doors.push_back({origin + glm::vec3(*offset, 0.0f, kMazeCell), {0.0f, 0.0f, 1.0f}, column, row + 1});
    }
    if (row > 0) {
        if (const auto offset = layout.southDoor[mazeCell(column, row - 1)])
            doors.push_back({origin + glm::vec3(*offset, 0.0f, 0.0f), {0.0f, 0.0f, -1.0f}, column, row - 1});
    }
    return doors;
}

// A camera at eye height 1.5 m from the wall opposite a door, looking through the door into the
// next room.
Camera makeDoorCamera(const std::string& name, const MazeDoor& door)
{
    return makeCamera(name, door.centre - (kMazeCell - 1.5f) * door.through + glm::vec3(0.0f, 1.6f, 0.0f),
                      door.centre + 3.0f * door.through + glm::vec3(0.0f, 1.3f, 0.0f), 60.0f, 0.05f, 100.0f);
}

Scene makeMaze()
{
    Scene scene = newScene("maze");
    const int floorMaterial = addMaterial(scene, "floor", glm::vec3(0.42f, 0.33f, 0.24f));
    const int ceilingMaterial = addMaterial(scene, "ceiling", glm::vec3(0.8f, 0.79f, 0.76f));
    const int plaster = addMaterial(scene, "wall_plaster", glm::vec3(0.75f, 0.72f, 0.65f));
    const int sage = addMaterial(scene, "wall_sage", glm::vec3(0.45f, 0.55f, 0.42f));
    const int terracotta = addMaterial(scene, "wall_terracotta", glm::vec3(0.65f, 0.38f, 0.28f));
    const int stone = addMaterial(scene, "stone", glm::vec3(0.6f, 0.58f, 0.55f));
    const int wood = addMaterial(scene, "wood", glm::vec3(0.5f, 0.35f, 0.2f));
    const int glossy = addMaterial(scene, "lacquer", glm::vec3(0.2f, 0.3f, 0.6f), 0.3f, 1.0f);

    std::mt19937 engine(kMazeSeed);
    const MazeLayout layout = makeMazeLayout(engine);

    // Floor and ceiling reach the outer faces of the outer walls.
    const glm::vec3 lower = mazeCellOrigin(0, 0) - glm::vec3(0.5f * kMazeWall, 0.0f, 0.5f * kMazeWall);
    const glm::vec3 size(kMazeColumns * kMazeCell + kMazeWall, 0.0f, kMazeRows * kMazeCell + kMazeWall);
    Mesh floor = newMesh("floor", floorMaterial);
    addRect(floor, lower, glm::vec3(0.0f, 0.0f, size.z), glm::vec3(size.x, 0.0f, 0.0f), kMazeTessellation); // faces up
    Mesh ceiling = newMesh("ceiling", ceilingMaterial);
    addRect(ceiling, lower + glm::vec3(0.0f, kMazeHeight, 0.0f), glm::vec3(size.x, 0.0f, 0.0f),
            glm::vec3(0.0f, 0.0f, size.z), kMazeTessellation); // faces down
    placeMesh(scene, std::move(floor));
    placeMesh(scene, std::move(ceiling));

    Mesh outer = newMesh("walls_outer", plaster), alongZ = newMesh("walls_z", sage),
         alongX = newMesh("walls_x", terracotta);
    addMazeWalls(layout, outer, alongZ, alongX);
    placeMesh(scene, std::move(outer));
    placeMesh(scene, std::move(alongZ));
    placeMesh(scene, std::move(alongX));

    addMazeFurniture(scene, engine, stone, glossy, wood);

    for (std::size_t i = 0; i < kMazeLamps.size(); ++i) {
        const MazeLamp& lamp = kMazeLamps[i];
        const glm::vec3 position =
            mazeCellOrigin(lamp.column, lamp.row) + glm::vec3(0.5f * kMazeCell, kLampHeight, 0.5f * kMazeCell);
        scene.lights.push_back(makePointLight("lamp" + std::to_string(i), position, lamp.color, lamp.intensity));
    }

    // "default": the first lamp's room, looking through its first door. "unlit": the first room
    // without a lamp that has a door into a lit room, looking into the lit room.
    scene.cameras.push_back(makeDoorCamera("default", mazeDoors(layout, kMazeLamps[0].column, kMazeLamps[0].row)[0]));
    for (int row = 0; row < kMazeRows && scene.cameras.size() < 2; ++row) {
        for (int column = 0; column < kMazeColumns && scene.cameras.size() < 2; ++column) {
            if (mazeCellIsLit(column, row)) continue;
            for (const MazeDoor& door : mazeDoors(layout, column, row)) {
                if (!mazeCellIsLit(door.nextColumn, door.nextRow)) continue;
                scene.cameras.push_back(makeDoorCamera("unlit", door));
                break;
            }
        }
    }
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// street

constexpr float kStreetHalfLength = 80.0f; // the street runs along z from -80 to 80 m
constexpr float kRoadHalfWidth = 6.0f;     // 12 m of asphalt
constexpr float kSidewalkWidth = 3.0f;
constexpr float kCurbHeight = 0.15f;
constexpr float kFacadeX = kRoadHalfWidth + kSidewalkWidth; // building fronts at |x| = 9 m
constexpr float kStoreyHeight = 3.5f;
constexpr float kStreetTessellation = 2.0f;
constexpr std::uint32_t kStreetSeed = 7u;

struct StreetMeshes {
    std::vector<Mesh> facades; // one per facade colour
    Mesh trim;                 // ledges, sills, cornices
    Mesh glass;                // the glossy windows
};

// Builds boxes relative to a building's street facade: `along` is z, `up` is y and `out` is the
// distance in front of the facade (towards the street) or, negative, behind it.
struct FacadeFrame {
    float side; // -1: the -x side of the street (facade faces +x), +1: the +x side

    void box(Mesh& mesh, float along0, float along1, float up0, float up1, float out0, float out1) const
    {
        const float x0 = side * (kFacadeX - out0), x1 = side * (kFacadeX - out1);
        addBox(mesh, glm::vec3(std::min(x0, x1), up0, along0), glm::vec3(std::max(x0, x1), up1, along1),
               kStreetTessellation);
    }
};

// One building: the block, a glass shop front, storeys of windows with sills between ledges,
// and a cornice. Everything protrudes from the block, so no face is coplanar with a visible one.
void addBuilding(StreetMeshes& meshes, std::mt19937& engine, float side, float z0, float width,
                 float minHeight = 10.0f, unsigned heightSteps = 31)
{
    const FacadeFrame frame{side};
    const float height = minHeight + static_cast<float>(engine() % heightSteps);
    const float depth = 14.0f + static_cast<float>(engine() % 7);
    Mesh& facade = meshes.facades[engine() % meshes.facades.size()];
    const float z1 = z0 + width;
    frame.box(facade, z0, z1, 0.0f, height, -depth, 0.0f);

    const int storeys = static_cast<int>(height / kStoreyHeight);
    const int bays = std::max(1, static_cast<int>(width / 2.5f));
    const float bay = width / static_cast<float>(bays);
    frame.box(meshes.glass, z0 + 0.15f * width, z1 - 0.15f * width, 0.4f, 3.0f, 0.0f, 0.04f); // shop front
    for (int storey = 1; storey < storeys; ++storey) {
        const float floorY = storey * kStoreyHeight;
        frame.box(meshes.trim, z0, z1, floorY - 0.1f, floorY + 0.1f, 0.0f, 0.25f); // ledge
        for (int b = 0; b < bays; ++b) {
            const float centre = z0 + (static_cast<float>(b) + 0.5f) * bay;
            frame.box(meshes.glass, centre - 0.6f, centre + 0.6f, floorY + 0.9f, floorY + 2.5f, 0.0f, 0.04f);
            frame.box(meshes.trim, centre - 0.7f, centre + 0.7f, floorY + 0.8f, floorY + 0.9f, 0.0f, 0.15f); // sill
        }
    }
    frame.box(meshes.trim, z0, z1, height - 0.5f, height, 0.0f, 0.4f); // cornice
}

void addStreetProps(Mesh& poles, Mesh& bark, Mesh& foliage, Mesh& benches)
{
    // Alternating street lamps and trees near both curbs, benches between them.
    int index = 0;
    for (float z = -kStreetHalfLength + 8.0f; z < kStreetHalfLength; z += 16.0f, ++index) {
        for (float side : {-1.0f, 1.0f}) {
            const float x = side * (kRoadHalfWidth + 0.6f);
            if ((index + (side > 0.0f ? 1 : 0)) % 2 == 0) {
                addCylinder(poles, glm::vec3(x, kCurbHeight, z), 0.08f, 6.0f, 12, 3, true);
                const float armX = side * (kRoadHalfWidth - 0.6f);
                addBox(poles, glm::vec3(std::min(x, armX), 6.0f, z - 0.08f),
                       glm::vec3(std::max(x, armX), 6.15f, z + 0.08f), kStreetTessellation);
                addBox(poles, glm::vec3(armX - 0.25f, 5.9f, z - 0.2f), glm::vec3(armX + 0.25f, 6.05f, z + 0.2f),
                       kStreetTessellation);
            } else {
                addCylinder(bark, glm::vec3(x, kCurbHeight, z), 0.15f, 3.0f, 12, 3, true);
                addSphere(foliage, glm::vec3(x, kCurbHeight + 4.2f, z), 1.6f, 12, 24, false);
            }
            const float benchX = side * (kFacadeX - 1.0f);
            addBox(benches, glm::vec3(benchX - 0.25f, kCurbHeight, z + 4.0f),
                   glm::vec3(benchX + 0.25f, kCurbHeight + 0.45f, z + 6.0f), kStreetTessellation);
        }
    }
}

using FacadeColours = std::vector<std::pair<const char*, glm::vec3>>;

// The street's building meshes: trim and glass (shared materials) and one facade mesh per colour.
StreetMeshes newStreetMeshes(Scene& scene, const FacadeColours& facadeColours)
{
    const int trim = addMaterial(scene, "trim", glm::vec3(0.3f, 0.29f, 0.27f));
    const int glass = addMaterial(scene, "glass", glm::vec3(0.05f, 0.06f, 0.07f), 0.25f, 1.0f);
    StreetMeshes meshes{{}, newMesh("trim", trim), newMesh("glass", glass)};
    for (const auto& [name, albedo] : facadeColours)
        meshes.facades.push_back(newMesh(name, addMaterial(scene, name, albedo)));
    return meshes;
}

// Asphalt between the curbs and raised sidewalks up to the facades, for z in [-halfLength, halfLength].
void addRoadAndSidewalks(Scene& scene, float halfLength)
{
    Mesh road = newMesh("road", addMaterial(scene, "asphalt", glm::vec3(0.1f)));
    addRect(road, glm::vec3(-kRoadHalfWidth, 0.0f, -halfLength), glm::vec3(0.0f, 0.0f, 2.0f * halfLength),
            glm::vec3(2.0f * kRoadHalfWidth, 0.0f, 0.0f), kStreetTessellation);
    Mesh walks = newMesh("sidewalks", addMaterial(scene, "sidewalk", glm::vec3(0.35f, 0.34f, 0.32f)));
    for (float side : {-1.0f, 1.0f}) {
        const float x0 = side * kRoadHalfWidth, x1 = side * kFacadeX;
        addBox(walks, glm::vec3(std::min(x0, x1), 0.0f, -halfLength),
               glm::vec3(std::max(x0, x1), kCurbHeight, halfLength), kStreetTessellation);
    }
    placeMesh(scene, std::move(road));
    placeMesh(scene, std::move(walks));
}

// The street's sun: warm, 4.5 W/m^2 on a surface facing it, `elevation` degrees above the horizon,
// its light travelling along `horizontal` (the +y-free part of its direction).
Light makeStreetSun(float elevationDegrees, const glm::vec3& horizontal)
{
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    const float elevation = glm::radians(elevationDegrees);
    sun.direction = glm::normalize(std::cos(elevation) * glm::normalize(horizontal) +
                                   glm::vec3(0.0f, -std::sin(elevation), 0.0f));
    sun.color = glm::vec3(1.0f, 0.88f, 0.72f);
    sun.intensity = 4.5f; // irradiance [W/m^2] on a surface facing the sun
    return sun;
}

Scene makeStreet()
{
    Scene scene = newScene("street");
    const int ground = addMaterial(scene, "ground", glm::vec3(0.22f, 0.21f, 0.19f));
    const int metal = addMaterial(scene, "pole", glm::vec3(0.15f));
    const int barkMaterial = addMaterial(scene, "bark", glm::vec3(0.25f, 0.18f, 0.12f));
    const int foliageMaterial = addMaterial(scene, "foliage", glm::vec3(0.12f, 0.3f, 0.08f));
    const int woodMaterial = addMaterial(scene, "bench", glm::vec3(0.45f, 0.3f, 0.18f));

    StreetMeshes meshes = newStreetMeshes(scene, {{"facade_cream", {0.7f, 0.64f, 0.52f}},
                                                  {"facade_brick", {0.45f, 0.22f, 0.15f}},
                                                  {"facade_grey", {0.5f, 0.5f, 0.5f}},
                                                  {"facade_ochre", {0.62f, 0.45f, 0.25f}}});

    std::mt19937 engine(kStreetSeed);
    for (float side : {-1.0f, 1.0f}) {
        float z = -kStreetHalfLength;
        while (z < kStreetHalfLength - 8.0f) {
            if (engine() % 6 == 0) z += 4.0f; // an alley
            const float width = std::min(8.0f + static_cast<float>(engine() % 13), kStreetHalfLength - z);
            if (width < 8.0f) break;
            addBuilding(meshes, engine, side, z, width);
            z += width;
        }
    }

    // Ground: asphalt between the curbs, raised sidewalks, and a wide plane around (four pieces,
    // so nothing overlaps the asphalt).
    addRoadAndSidewalks(scene, kStreetHalfLength);
    Mesh plane = newMesh("ground", ground);
    constexpr float kGroundHalf = 100.0f, kGroundCell = 10.0f; // small: the shadow map covers the scene bounds
    const glm::vec3 alongZ(0.0f, 0.0f, 1.0f), alongX(1.0f, 0.0f, 0.0f); // z cross x = +y: faces up
    addRect(plane, glm::vec3(-kGroundHalf, 0.0f, -kGroundHalf), 2.0f * kGroundHalf * alongZ,
            (kGroundHalf - kRoadHalfWidth) * alongX, kGroundCell);
    addRect(plane, glm::vec3(kRoadHalfWidth, 0.0f, -kGroundHalf), 2.0f * kGroundHalf * alongZ,
            (kGroundHalf - kRoadHalfWidth) * alongX, kGroundCell);
    for (float z0 : {-kGroundHalf, kStreetHalfLength})
        addRect(plane, glm::vec3(-kRoadHalfWidth, 0.0f, z0), (kGroundHalf - kStreetHalfLength) * alongZ,
                2.0f * kRoadHalfWidth * alongX, kGroundCell);

    Mesh poles = newMesh("lamp_posts", metal), bark = newMesh("tree_trunks", barkMaterial),
         foliage = newMesh("tree_crowns", foliageMaterial), benches = newMesh("benches", woodMaterial);
    addStreetProps(poles, bark, foliage, benches);

    for (Mesh& facade : meshes.facades) placeMesh(scene, std::move(facade));
    for (Mesh* mesh : {&meshes.trim, &meshes.glass, &plane, &poles, &bark, &foliage, &benches})
        placeMesh(scene, std::move(*mesh));

    // The sun at 40 degrees elevation on the +x side (and somewhat towards +z): its light travels
    // across the street towards -x, so the +x side's facades (facing -x) and most of the street lie
    // in shadow while the upper floors of the -x side are sunlit.
    scene.lights.push_back(makeStreetSun(40.0f, glm::vec3(-1.0f, 0.0f, -0.8f)));

    scene.cameras.push_back(
        makeCamera("default", glm::vec3(-2.5f, 1.7f, 70.0f), glm::vec3(1.0f, 4.0f, 0.0f), 60.0f, 0.1f, 800.0f));
    scene.cameras.push_back(
        makeCamera("aerial", glm::vec3(90.0f, 120.0f, 140.0f), glm::vec3(0.0f), 50.0f, 1.0f, 1000.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// canyon (LightSkin + BRSM, Fig. 6: "a commonly employed urban street scene" with "some colored
// planes to illustrate color bleeding": the buildings on one side are lit by the light the planes
// reflect)

constexpr float kCanyonHalfLength = 24.0f; // a 48 m stretch of street, open at both ends
constexpr std::uint32_t kCanyonSeed = 11u;
constexpr float kCanyonSunElevation = 55.0f;    // degrees: high enough to light the -x half of the road
constexpr float kCanyonBoardTilt = 30.0f;       // degrees from vertical, leaning towards -x

Scene makeCanyon()
{
    Scene scene = newScene("canyon");
    // Light facades, so that the boards' colours show on them.
    StreetMeshes meshes = newStreetMeshes(scene, {{"facade_white", {0.75f, 0.74f, 0.72f}},
                                                  {"facade_cream", {0.7f, 0.64f, 0.52f}},
                                                  {"facade_grey", {0.55f, 0.55f, 0.55f}}});

    // Buildings of 10-16 m on the +x side (towards the sun: they shade the +x half of the street
    // and their own facades), 12-30 m on the -x side.
    std::mt19937 engine(kCanyonSeed);
    for (float side : {-1.0f, 1.0f}) {
        float z = -kCanyonHalfLength;
        while (z < kCanyonHalfLength - 8.0f) {
            const float width = std::min(8.0f + static_cast<float>(engine() % 9), kCanyonHalfLength - z);
            if (width < 8.0f) break;
            if (side > 0.0f)
                addBuilding(meshes, engine, side, z, width, 10.0f, 7);
            else
                addBuilding(meshes, engine, side, z, width, 12.0f, 19);
            z += width;
        }
    }
    addRoadAndSidewalks(scene, kCanyonHalfLength);
    for (Mesh& facade : meshes.facades) placeMesh(scene, std::move(facade));
    for (Mesh* mesh : {&meshes.trim, &meshes.glass}) placeMesh(scene, std::move(*mesh));

    // Three saturated boards (5 m x 4 m, 5 cm thick) on the sunlit -x half of the road, leaning
    // back so that their fronts face the sun and the shaded +x facades.
    const std::array<std::pair<const char*, glm::vec3>, 3> boards{{
        {"board_red", {0.8f, 0.08f, 0.06f}},
        {"board_green", {0.1f, 0.7f, 0.12f}},
        {"board_blue", {0.08f, 0.15f, 0.8f}},
    }};
    for (std::size_t i = 0; i < boards.size(); ++i) {
        Mesh board = newMesh(boards[i].first, addMaterial(scene, boards[i].first, boards[i].second));
        addBox(board, glm::vec3(0.0f, 0.0f, -2.5f), glm::vec3(0.05f, 4.0f, 2.5f), 0.5f);
        const float z = -14.0f + 14.0f * static_cast<float>(i);
        const glm::mat4 at = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f, 0.0f, z)),
                                         glm::radians(kCanyonBoardTilt), glm::vec3(0.0f, 0.0f, 1.0f));
        addInstance(scene, addMesh(scene, std::move(board)), at);
    }

    // The sun from the +x side, a little towards +z, at 55 degrees (scenes/canyon-sun.json moves it).
    scene.lights.push_back(makeStreetSun(kCanyonSunElevation, glm::vec3(-1.0f, 0.0f, -0.3f)));

    // A pedestrian on the -x sidewalk looking across at the shaded +x facades (scenes/canyon-walk.json
    // walks it down the street), and a view from above.
    scene.cameras.push_back(
        makeCamera("default", glm::vec3(-7.5f, 1.7f, -20.0f), glm::vec3(6.0f, 4.0f, -4.0f), 60.0f, 0.1f, 300.0f));
    scene.cameras.push_back(
        makeCamera("aerial", glm::vec3(-30.0f, 45.0f, 40.0f), glm::vec3(0.0f, 0.0f, 0.0f), 50.0f, 1.0f, 500.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// glossy (VSGL Fig. 1 and 5: glossy, normal-mapped surfaces lit by a moving light)

constexpr float kGlossyHalfWidth = 5.0f;   // the room spans x in [-5, 5] m
constexpr float kGlossyHalfDepth = 4.0f;   // z in [-4, 4] m
constexpr float kGlossyHeight = 4.0f;      // floor to ceiling [m]
constexpr float kGlossyTessellation = 0.5f;
// VSGL's Phong exponent 1023 corresponds to GGX alpha = sqrt(2 / (1023 + 2)) = 0.044, i.e.
// roughness 0.21 (MATH.md, Blinn-Phong vs microfacet NDFs); the glossy surfaces here use 0.25-0.3.
constexpr float kGlossyRoughness = 0.3f;

// Adds a glossy dielectric (F0 = 0.04) with a normal map.
int addNormalMappedMaterial(Scene& scene, const std::string& name, const glm::vec3& albedo, float roughness,
                            int normalImage)
{
    const int index = addMaterial(scene, name, albedo, roughness, 1.0f);
    scene.materials[static_cast<std::size_t>(index)].normalTexture.image = normalImage;
    return index;
}

int addImage(Scene& scene, Image image)
{
    scene.images.push_back(std::move(image));
    return static_cast<int>(scene.images.size()) - 1;
}

Scene makeGlossy()
{
    Scene scene = newScene("glossy");
    const int tiles = addImage(scene, makeTileNormalMap());
    const int bumps = addImage(scene, makeBumpNormalMap());
    const int floorMaterial = addNormalMappedMaterial(scene, "floor_tiles", glm::vec3(0.55f, 0.5f, 0.45f),
                                                      kGlossyRoughness, tiles);
    const int panelMaterial = addNormalMappedMaterial(scene, "wall_panels", glm::vec3(0.35f, 0.42f, 0.55f),
                                                      0.25f, bumps);
    const int lacquer = addNormalMappedMaterial(scene, "lacquer_bumps", glm::vec3(0.6f, 0.12f, 0.1f),
                                                kGlossyRoughness, bumps);
    const int brass = addMaterial(scene, "brass", glm::vec3(0.91f, 0.72f, 0.42f), 0.25f, 1.0f);
    scene.materials[static_cast<std::size_t>(brass)].metallic = 1.0f;
    const int white = addMaterial(scene, "plaster", glm::vec3(0.75f, 0.74f, 0.72f));
    const int red = addMaterial(scene, "wall_red", glm::vec3(0.62f, 0.12f, 0.08f));
    const int green = addMaterial(scene, "wall_green", glm::vec3(0.14f, 0.45f, 0.2f));
    const int ochre = addMaterial(scene, "ochre", glm::vec3(0.7f, 0.5f, 0.18f));

    // The room, every face towards the inside. Tiles of 0.5 m on the floor, 0.4 m panels on the
    // back wall; the other walls and the ceiling are diffuse.
    const float x0 = -kGlossyHalfWidth, x1 = kGlossyHalfWidth, z0 = -kGlossyHalfDepth, z1 = kGlossyHalfDepth;
    const glm::vec3 width(x1 - x0, 0.0f, 0.0f), depth(0.0f, 0.0f, z1 - z0), height(0.0f, kGlossyHeight, 0.0f);
    Mesh floor = newMesh("floor", floorMaterial);
    addRect(floor, glm::vec3(x0, 0.0f, z0), depth, width, kGlossyTessellation, 0.5f); // z cross x = +y
    Mesh back = newMesh("back_wall", panelMaterial);
    addRect(back, glm::vec3(x0, 0.0f, z0), width, height, kGlossyTessellation, 0.4f); // x cross y = +z
    Mesh ceiling = newMesh("ceiling", white), front = newMesh("front_wall", white);
    addRect(ceiling, glm::vec3(x0, kGlossyHeight, z0), width, depth, kGlossyTessellation); // -y
    addRect(front, glm::vec3(x0, 0.0f, z1), height, width, kGlossyTessellation);           // -z
    Mesh left = newMesh("left_wall", red), right = newMesh("right_wall", green);
    addRect(left, glm::vec3(x0, 0.0f, z0), height, depth, kGlossyTessellation);  // y cross z = +x
    addRect(right, glm::vec3(x1, 0.0f, z0), depth, height, kGlossyTessellation); // -x
    generateTangents(floor);
    generateTangents(back);
    for (Mesh* mesh : {&floor, &back, &ceiling, &front, &left, &right}) placeMesh(scene, std::move(*mesh));

    // Objects: a pedestal carrying a brass sphere, a bumpy lacquered block turned 25 degrees, and a
    // column from floor to ceiling. None is on the spot light's path (see glossy-moving-light.json).
    Mesh pedestal = newMesh("pedestal", white);
    addBox(pedestal, glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 0.9f, 0.4f), kGlossyTessellation);
    Mesh sphere = newMesh("sphere", brass);
    addSphere(sphere, glm::vec3(0.0f, 1.35f, 0.0f), 0.45f, 24, 48, false);
    Mesh block = newMesh("block", lacquer);
    addBox(block, glm::vec3(-0.7f, 0.0f, -0.5f), glm::vec3(0.7f, 0.7f, 0.5f), kGlossyTessellation, 0.35f);
    generateTangents(block);
    Mesh column = newMesh("column", ochre);
    addCylinder(column, glm::vec3(0.0f), 0.3f, kGlossyHeight, 32, 4, false); // floor to ceiling: no caps
    const glm::mat4 pedestalAt = glm::translate(glm::mat4(1.0f), glm::vec3(-2.2f, 0.0f, -1.8f));
    const int pedestalMesh = addMesh(scene, std::move(pedestal));
    const int sphereMesh = addMesh(scene, std::move(sphere));
    addInstance(scene, pedestalMesh, pedestalAt);
    addInstance(scene, sphereMesh, pedestalAt);
    addInstance(scene, addMesh(scene, std::move(block)),
                glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.8f, 0.0f, -1.6f)), glm::radians(25.0f),
                            glm::vec3(0.0f, 1.0f, 0.0f)));
    addInstance(scene, addMesh(scene, std::move(column)), glm::translate(glm::mat4(1.0f), glm::vec3(3.2f, 0.0f, 1.5f)));

    // A warm spot under the ceiling, 2.9 m from the room's axis at 150 degrees (from +x towards +z),
    // aimed down across the axis at the glossy floor 1.2 m beyond it: the floor's highlight throws
    // glossy light onto the walls and the objects. scenes/glossy-moving-light.json moves it around
    // the axis in 45 degree steps, starting here.
    const glm::vec3 around(std::cos(glm::radians(150.0f)), 0.0f, std::sin(glm::radians(150.0f)));
    scene.lights.push_back(makeSpotLight("spot", 2.9f * around + glm::vec3(0.0f, 3.6f, 0.0f), -1.2f * around,
                                         glm::vec3(1.0f, 0.9f, 0.75f), 60.0f, 25.0f, 40.0f));

    scene.cameras.push_back(
        makeCamera("default", glm::vec3(0.0f, 1.7f, 3.7f), glm::vec3(0.0f, 1.0f, -2.0f), 60.0f, 0.05f, 50.0f));
    scene.cameras.push_back(
        makeCamera("corner", glm::vec3(4.5f, 3.0f, 3.5f), glm::vec3(-1.0f, 0.5f, -1.5f), 60.0f, 0.05f, 50.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// sealed (conform's leak test): a room lit through a roof window beside a closed room

// The inside of the box [lower, upper], every face towards the inside, without its ceiling.
void addRoomWithoutCeiling(Mesh& mesh, const glm::vec3& lower, const glm::vec3& upper, float cell)
{
    const glm::vec3 size = upper - lower;
    const glm::vec3 dx(size.x, 0.0f, 0.0f), dy(0.0f, size.y, 0.0f), dz(0.0f, 0.0f, size.z);
    addRect(mesh, lower, dz, dx, cell);                                // floor, +y
    addRect(mesh, lower, dy, dz, cell);                                // x = lower.x, +x
    addRect(mesh, glm::vec3(upper.x, lower.y, lower.z), dz, dy, cell); // x = upper.x, -x
    addRect(mesh, lower, dx, dy, cell);                                // z = lower.z, +z
    addRect(mesh, glm::vec3(lower.x, lower.y, upper.z), dy, dx, cell); // z = upper.z, -z
}

// The rectangle x in [x0, x1], z in [z0, z1] at height y, facing down (-y) or up (+y), minus the
// hole [hx0, hx1] x [hz0, hz1] (an empty hole: the whole rectangle).
void addSlabFace(Mesh& mesh, float y, float x0, float x1, float z0, float z1, const glm::vec4& hole, bool up,
                 float cell)
{
    auto rect = [&](float a0, float a1, float b0, float b1) {
        if (!(a1 > a0) || !(b1 > b0)) return;
        const glm::vec3 dx(a1 - a0, 0.0f, 0.0f), dz(0.0f, 0.0f, b1 - b0), origin(a0, y, b0);
        if (up) addRect(mesh, origin, dz, dx, cell); // z cross x = +y
        else addRect(mesh, origin, dx, dz, cell);    // x cross z = -y
    };
    if (!(hole.y > hole.x)) {
        rect(x0, x1, z0, z1);
        return;
    }
    rect(x0, hole.x, z0, z1);
    rect(hole.y, x1, z0, z1);
    rect(hole.x, hole.y, z0, hole.z);
    rect(hole.x, hole.y, hole.w, z1);
}

// Two rooms side by side along x behind solid walls 10 cm thick: the lit room (x in [-4, 0]) has a
// 2 x 2 m window in its roof, the closed room (x in [0.1, 4.1]) has no opening at all, so no path
// of light reaches its inside and the path tracer gives exactly 0 there. Each room is its own mesh
// of single-sided faces towards its inside; the building's outer shell (walls, floor, roof around
// the window, the window's reveals) faces outwards. Both floors lie in one plane with one normal,
// as do both ceilings, on either side of the shared wall: what a leak through a wall joint, an
// imperfect shadow map or a cache interpolated across the wall shows. Cameras: "default" (in the lit
// room) and "closed"; `light` picks the one light: "sun" (through the window), "point", "spot", "emissive".
Scene makeSealed(const std::string& light)
{
    Scene scene = newScene(light == "sun" ? "sealed" : "sealed-" + light);
    const int white = addMaterial(scene, "plaster", glm::vec3(0.7f));
    const float cell = 0.5f, height = 3.0f, wall = 0.1f;
    const glm::vec4 window(-3.0f, -1.0f, -1.0f, 1.0f); // x0, x1, z0, z1 of the roof window
    const glm::vec4 none(0.0f);

    // The lit room: floor and walls, the ceiling around the window; the closed room, all six faces.
    Mesh lit = newMesh("lit room", white);
    addRoomWithoutCeiling(lit, glm::vec3(-4.0f, 0.0f, -2.0f), glm::vec3(0.0f, height, 2.0f), cell);
    addSlabFace(lit, height, -4.0f, 0.0f, -2.0f, 2.0f, window, false, cell);
    Mesh closed = newMesh("closed room", white);
    addRoomWithoutCeiling(closed, glm::vec3(0.1f, 0.0f, -2.0f), glm::vec3(4.1f, height, 2.0f), cell);
    addSlabFace(closed, height, 0.1f, 4.1f, -2.0f, 2.0f, none, false, cell);

    // The outer shell, facing out, and the window's reveals through the roof, facing into the hole.
    Mesh shell = newMesh("shell", white);
    const glm::vec3 lower(-4.0f - wall, -wall, -2.0f - wall), upper(4.1f + wall, height + wall, 2.0f + wall);
    const glm::vec3 size = upper - lower;
    const glm::vec3 dx(size.x, 0.0f, 0.0f), dy(0.0f, size.y, 0.0f), dz(0.0f, 0.0f, size.z);
    addRect(shell, glm::vec3(upper.x, lower.y, lower.z), dy, dz, cell); // +x
    addRect(shell, lower, dz, dy, cell);                                // -x
    addRect(shell, lower, dx, dz, cell);                                // -y
    addRect(shell, glm::vec3(lower.x, lower.y, upper.z), dx, dy, cell); // +z
    addRect(shell, lower, dy, dx, cell);                                // -z
    addSlabFace(shell, upper.y, lower.x, upper.x, lower.z, upper.z, window, true, cell);
    const glm::vec3 reveal(0.0f, wall, 0.0f), wx(window.y - window.x, 0.0f, 0.0f), wz(0.0f, 0.0f, window.w - window.z);
    addRect(shell, glm::vec3(window.x, height, window.z), reveal, wz, cell); // +x
    addRect(shell, glm::vec3(window.y, height, window.z), wz, reveal, cell); // -x
    addRect(shell, glm::vec3(window.x, height, window.z), wx, reveal, cell); // +z
    addRect(shell, glm::vec3(window.x, height, window.w), reveal, wx, cell); // -z

    if (light == "emissive") {
        // A 0.6 x 0.6 m panel just under the lit room's ceiling, facing down.
        const int panel = addMaterial(scene, "panel", glm::vec3(0.0f));
        scene.materials[static_cast<std::size_t>(panel)].emission = glm::vec3(12.0f);
        Mesh lamp = newMesh("panel", panel);
        addSlabFace(lamp, height - 0.01f, -3.8f, -3.2f, -1.8f, -1.2f, none, false, 1.0f);
        placeMesh(scene, std::move(lamp));
    } else if (light == "point") {
        scene.lights.push_back(makePointLight("lamp", glm::vec3(-2.0f, 2.2f, 0.0f), glm::vec3(1.0f), 6.0f));
    } else if (light == "spot") {
        scene.lights.push_back(makeSpotLight("spot", glm::vec3(-3.6f, 2.6f, 1.6f), glm::vec3(-1.5f, 0.0f, -0.5f),
                                             glm::vec3(1.0f), 30.0f, 20.0f, 30.0f));
    } else {
        Light sun;
        sun.name = "sun";
        sun.type = LightType::Directional;
        sun.direction = glm::normalize(glm::vec3(0.25f, -1.0f, 0.15f));
        sun.intensity = 3.0f;
        scene.lights.push_back(sun);
    }
    for (Mesh* mesh : {&lit, &closed, &shell}) placeMesh(scene, std::move(*mesh));
    scene.cameras.push_back(makeCamera("default", glm::vec3(-0.4f, 1.7f, 1.7f), glm::vec3(-2.6f, 0.6f, -1.0f), 70.0f,
                                       0.05f, 30.0f));
    scene.cameras.push_back(makeCamera("closed", glm::vec3(3.8f, 1.7f, 1.7f), glm::vec3(0.6f, 0.8f, -1.4f), 70.0f,
                                       0.05f, 30.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// board (LightSkin's occlusion, issue "LightSkin's indirect shadows"): a broad sunlit floor, a wall
// at its edge that the sun does not reach, and a 2.5 m board standing 2 m in front of the wall.
// Below the board's top the wall sees the floor beyond the board only through the board: its
// one-bounce light comes from the 2 m strip in front of it (about half of what the open floor
// would give at 1 m height, 2D view factors sin(atan(h/2))/2 of 1/2). The sun travels along the
// board's plane, so the board casts no direct shadow on the strip and the wall gets no direct light.

Scene makeBoard()
{
    Scene scene = newScene("board");
    const int grey = addMaterial(scene, "grey", glm::vec3(0.7f));
    const float cell = 0.5f;
    Mesh ground = newMesh("floor", grey);
    addRect(ground, glm::vec3(0.0f, 0.0f, -12.0f), glm::vec3(0.0f, 0.0f, 24.0f), glm::vec3(24.0f, 0.0f, 0.0f), cell);
    Mesh wall = newMesh("wall", grey); // x = 0, facing +x
    addRect(wall, glm::vec3(0.0f, 0.0f, -12.0f), glm::vec3(0.0f, 4.0f, 0.0f), glm::vec3(0.0f, 0.0f, 24.0f), cell);
    Mesh board = newMesh("board", grey); // 12 m long, 2.5 m high, 10 cm thick
    addBox(board, glm::vec3(1.95f, 0.0f, -6.0f), glm::vec3(2.05f, 2.5f, 6.0f), cell);
    for (Mesh* mesh : {&ground, &wall, &board}) placeMesh(scene, std::move(*mesh));
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.3f)); // no x component: parallel to wall and board
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    // "default": between the board and the wall, looking at the wall the board shades (every
    // pixel in the board's indirect shadow); "open": the same view of the wall past the board's end.
    scene.cameras.push_back(makeCamera("default", glm::vec3(1.6f, 1.25f, 0.0f), glm::vec3(0.0f, 1.25f, 0.0f), 60.0f,
                                       0.05f, 60.0f));
    scene.cameras.push_back(makeCamera("open", glm::vec3(1.6f, 1.25f, 9.0f), glm::vec3(0.0f, 1.25f, 9.0f), 60.0f,
                                       0.05f, 60.0f));
    scene.validate();
    return scene;
}

// ---------------------------------------------------------------------------------------------
// cutout

// The leaf of the cutout scene: one colour, alpha 255 inside a lens (the intersection of two discs,
// its axis along the texture's diagonal) less three round bites, alpha 0 elsewhere; 31% of the
// texels are kept (tests/cpu/test_alpha_masks.cpp measures it).
Image makeLeafImage(int size)
{
    Image image;
    image.name = "leaf";
    image.width = image.height = size;
    image.rgba.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 4);
    const glm::vec2 axis = glm::normalize(glm::vec2(1.0f, 1.0f)), across(-axis.y, axis.x);
    const glm::vec2 centre(0.5f);
    const glm::vec2 bites[3] = {{0.40f, 0.44f}, {0.63f, 0.60f}, {0.50f, 0.36f}};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec2 uv((x + 0.5f) / size, (y + 0.5f) / size);
            // Lens: within 0.8 of two centres 0.58 either side of the axis (0.44 wide, tips 1.1 apart).
            const bool lens = glm::distance(uv, centre + 0.58f * across) < 0.8f &&
                              glm::distance(uv, centre - 0.58f * across) < 0.8f;
            bool bitten = false;
            for (const glm::vec2& b : bites) bitten = bitten || glm::distance(uv, b) < 0.05f;
            std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * size + x) * 4];
            p[0] = 200;
            p[1] = 190;
            p[2] = 160;
            p[3] = lens && !bitten ? 255 : 0;
        }
    return image;
}

// An alpha-masked leaf standing on a floor (issue 28's test scene): a 2 m x 1.8 m double-sided panel
// at z = 0 whose base colour texture cuts out a leaf (MASK, cutoff 0.5), a spot light in front
// (+z) that lights it and shines through the cut-away part onto the floor behind, which receives the
// leaf's shadow; the floor in front receives the light the leaf bounces. Cameras: "default"
// (oblique), "behind" and "front" (straight down onto the floor behind and in front of the panel;
// neither sees the panel).
Scene makeCutout()
{
    Scene scene = newScene("cutout");
    const int floorMaterial = addMaterial(scene, "floor", glm::vec3(0.6f));
    const int leafMaterial = addMaterial(scene, "leaf", glm::vec3(1.0f));
    scene.images.push_back(makeLeafImage(128));
    Material& leaf = scene.materials[static_cast<std::size_t>(leafMaterial)];
    leaf.baseColorTexture.image = static_cast<int>(scene.images.size()) - 1;
    leaf.alphaMode = Material::AlphaMode::Mask;
    leaf.alphaCutoff = 0.5f;
    leaf.doubleSided = true;

    Mesh floor = newMesh("floor", floorMaterial);
    addRect(floor, glm::vec3(-3.0f, 0.0f, -3.0f), glm::vec3(0.0f, 0.0f, 6.0f), glm::vec3(6.0f, 0.0f, 0.0f), 1.0f);
    placeMesh(scene, std::move(floor));
    Mesh panel = newMesh("leaf", leafMaterial);
    addRect(panel, glm::vec3(-1.0f, 0.1f, 0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.8f, 0.0f), 2.0f);
    placeMesh(scene, std::move(panel));

    // Aimed at the panel's centre; the 28-degree cone takes in the whole panel (its corners are 16-25
    // degrees off the axis) and lands on the floor behind it out to z = -2.4 m.
    scene.lights.push_back(makeSpotLight("spot", glm::vec3(0.0f, 3.5f, 2.0f), glm::vec3(0.0f, 0.9f, 0.0f),
                                         glm::vec3(1.0f), 30.0f, 26.0f, 28.0f));

    scene.cameras.push_back(makeCamera("default", glm::vec3(2.4f, 2.4f, 3.0f), glm::vec3(0.0f, 0.5f, -0.5f), 45.0f,
                                       0.05f, 30.0f));
    Camera behind = makeCamera("behind", glm::vec3(0.0f, 2.0f, -1.2f), glm::vec3(0.0f, 0.0f, -1.2f), 40.0f, 0.05f, 30.0f);
    behind.up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.cameras.push_back(behind);
    Camera front = makeCamera("front", glm::vec3(0.0f, 2.0f, 0.9f), glm::vec3(0.0f, 0.0f, 0.9f), 40.0f, 0.05f, 30.0f);
    front.up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.cameras.push_back(front);
    scene.validate();
    return scene;
}

// one-sided

// The back-face rule's test scene (issue 28 part 2; scene.h Material::doubleSided): two opaque
// single-sided grey panels (2 m x 1.8 m) side by side at z = 0 on a floor, a spot light in front
// (+z) that takes in both. Panel "facing" (x < 0) turns its front to the light: it casts a shadow
// behind and bounces light forward. Panel "away" (x > 0) is the same mesh placed with a mirror
// (scale z by -1: glTF's clockwise front) so that its front faces -z: from the light and from the
// default camera it is seen from behind, where it is absent: no shadow, no bounce, the floor behind
// it shows through. Cameras: "default" (oblique, in front), "behind" (oblique, behind the panels:
// the facing panel is absent, the away panel's front is seen), "front" (down onto the floor in front).
Scene makeOneSided()
{
    Scene scene = newScene("one-sided");
    const int floorMaterial = addMaterial(scene, "floor", glm::vec3(0.6f));
    const int panelMaterial = addMaterial(scene, "panel", glm::vec3(0.8f));
    Mesh floor = newMesh("floor", floorMaterial);
    addRect(floor, glm::vec3(-4.0f, 0.0f, -3.0f), glm::vec3(0.0f, 0.0f, 6.0f), glm::vec3(8.0f, 0.0f, 0.0f), 1.0f);
    placeMesh(scene, std::move(floor));
    Mesh facing = newMesh("facing", panelMaterial);
    addRect(facing, glm::vec3(-2.2f, 0.1f, 0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.8f, 0.0f), 2.0f);
    placeMesh(scene, std::move(facing));
    Mesh away = newMesh("away", panelMaterial); // front +z in object space
    addRect(away, glm::vec3(0.2f, 0.1f, 0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.8f, 0.0f), 2.0f);
    addInstance(scene, addMesh(scene, std::move(away)), glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, -1.0f)));

    // Aimed between the panels; the 45-degree cone takes in both (their outer corners are 33-38
    // degrees off the axis) and the floor behind them out to z = -2.5 m.
    scene.lights.push_back(makeSpotLight("spot", glm::vec3(0.0f, 3.5f, 2.5f), glm::vec3(0.0f, 0.9f, 0.0f),
                                         glm::vec3(1.0f), 30.0f, 40.0f, 45.0f));
    scene.cameras.push_back(makeCamera("default", glm::vec3(1.0f, 2.6f, 4.5f), glm::vec3(0.0f, 0.6f, -0.8f), 50.0f,
                                       0.05f, 30.0f));
    scene.cameras.push_back(makeCamera("behind", glm::vec3(-1.0f, 2.6f, -4.0f), glm::vec3(0.0f, 0.6f, 0.5f), 50.0f,
                                       0.05f, 30.0f));
    Camera front = makeCamera("front", glm::vec3(0.0f, 3.0f, 1.4f), glm::vec3(0.0f, 0.0f, 1.4f), 60.0f, 0.05f, 30.0f);
    front.up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.cameras.push_back(front);
    scene.validate();
    return scene;
}

} // namespace

std::vector<std::string> builtinSceneNames()
{
    return {"board", "canyon", "caustics", "cornell", "cutout", "furnace", "glossy", "maze", "one-sided", "sealed",
            "sealed-emissive", "sealed-point", "sealed-spot", "street"};
}

bool isBuiltinScene(const std::string& name)
{
    const std::vector<std::string> names = builtinSceneNames();
    return std::find(names.begin(), names.end(), name) != names.end();
}

Scene makeBuiltinScene(const std::string& name)
{
    if (name == "board") return makeBoard();
    if (name == "canyon") return makeCanyon();
    if (name == "caustics") return makeCaustics(CausticsParams{});
    if (name == "cornell") return makeCornell();
    if (name == "cutout") return makeCutout();
    if (name == "furnace") return makeFurnace(FurnaceParams{});
    if (name == "glossy") return makeGlossy();
    if (name == "maze") return makeMaze();
    if (name == "one-sided") return makeOneSided();
    if (name == "sealed") return makeSealed("sun");
    if (name == "sealed-emissive") return makeSealed("emissive");
    if (name == "sealed-point") return makeSealed("point");
    if (name == "sealed-spot") return makeSealed("spot");
    if (name == "street") return makeStreet();
    std::string known;
    for (const std::string& builtin : builtinSceneNames()) known += (known.empty() ? "" : ", ") + builtin;
    throw Error("unknown scene \"" + name + "\" (built-in scenes: " + known + ")");
}

Scene makeFurnace(const FurnaceParams& params)
{
    require(params.radius > 0.0f && params.rings >= 2 && params.segments >= 3,
            "furnace: need radius > 0, rings >= 2, segments >= 3");
    Scene scene = newScene("furnace");
    const int wall = addMaterial(scene, "wall", glm::vec3(params.albedo));
    Mesh sphere = newMesh("sphere", wall);
    addSphere(sphere, glm::vec3(0.0f), params.radius, params.rings, params.segments, true);
    placeMesh(scene, std::move(sphere));
    scene.lights.push_back(makePointLight("center", glm::vec3(0.0f), glm::vec3(1.0f), params.intensity));
    scene.cameras.push_back(
        makeCamera("default", glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 60.0f, 0.01f, 4.0f * params.radius));
    scene.validate();
    return scene;
}

double furnaceRadianceBounce(const FurnaceParams& params, int n)
{
    // n = 0 would be the walls' own emission, which is zero; the point light is not seen.
    if (n <= 0) return 0.0;
    const double r = params.radius;
    return std::pow(static_cast<double>(params.albedo), n) * params.intensity / (kPiDouble * r * r);
}

double furnaceRadianceAll(const FurnaceParams& params)
{
    // The series diverges for rho >= 1 (no absorption).
    if (params.albedo >= 1.0f) return HUGE_VAL;
    const double rho = params.albedo, r = params.radius;
    return rho * params.intensity / (kPiDouble * r * r * (1.0 - rho));
}

Scene makeCaustics(const CausticsParams& params)
{
    require(params.ringRadius > 0.0f && params.ringHeight > 0.0f && params.ringSegments >= 2 &&
                params.ringRoughness >= 0.0f && params.ringRoughness <= 1.0f,
            "caustics: need ringRadius > 0, ringHeight > 0, ringSegments >= 2, ringRoughness in [0,1]");
    Scene scene = newScene("caustics");
    const int floorMaterial = addMaterial(scene, "floor", glm::vec3(0.75f));
    const int ringMaterial = addMaterial(scene, "mirror_ring", glm::vec3(0.95f, 0.93f, 0.88f), params.ringRoughness,
                                         1.0f);
    scene.materials[static_cast<std::size_t>(ringMaterial)].metallic = 1.0f;

    // 6 m x 6 m of floor in 0.5 m cells: about 600 triangles with the ring (VSGL's scene has 514).
    constexpr float kFloorHalf = 3.0f;
    Mesh floor = newMesh("floor", floorMaterial);
    addRect(floor, glm::vec3(-kFloorHalf, 0.0f, -kFloorHalf), glm::vec3(0.0f, 0.0f, 2.0f * kFloorHalf),
            glm::vec3(2.0f * kFloorHalf, 0.0f, 0.0f), 0.5f); // z cross x = +y
    placeMesh(scene, std::move(floor));

    // 200 degrees of ring centred on -z, open towards +z where the light stands, so that the light
    // falls on its inside; 3 cm thick.
    Mesh ring = newMesh("ring", ringMaterial);
    const float halfArc = glm::radians(100.0f);
    addRingWall(ring, glm::vec3(0.0f), params.ringRadius, 0.03f * params.ringRadius, params.ringHeight,
                kPi - halfArc, kPi + halfArc, params.ringSegments);
    placeMesh(scene, std::move(ring));

    // The spot stands on the open side, 30-34 degrees above the far wall as seen from there. Seen
    // from above, the far wall images the light (mirror equation, object distance 3.6 R) at
    // 1 / (2/R - 1/(3.6 R)) = 0.58 R in front of the wall: the cusp of the caustic curve (a nephroid
    // for parallel light). A ray reflected at height y keeps falling at 30 degrees and lands 1.7 y
    // from the wall, so the floor receives the curve out to 1.7 x the wall height (1.04 R), past the cusp.
    const float r = params.ringRadius;
    scene.lights.push_back(makeSpotLight("spot", glm::vec3(0.0f, 2.4f * r, 2.6f * r),
                                         glm::vec3(0.0f, 0.3f * r, -0.5f * r), glm::vec3(1.0f, 0.95f, 0.85f),
                                         40.0f * r * r, 20.0f, 30.0f));

    scene.cameras.push_back(makeCamera("default", glm::vec3(1.2f, 2.2f, 3.0f) * r, glm::vec3(0.0f, 0.1f, -0.4f) * r,
                                       45.0f, 0.02f * r, 30.0f * r));
    // Straight down onto the ring (image up = -z): the floor inside the ring in one view.
    Camera top = makeCamera("top", glm::vec3(0.0f, 4.5f * r, 0.0f), glm::vec3(0.0f), 40.0f, 0.02f * r, 30.0f * r);
    top.up = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.cameras.push_back(top);
    scene.validate();
    return scene;
}

} // namespace vplgi
