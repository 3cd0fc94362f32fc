// glTF 2.0, FBX and OBJ through Assimp: every triangle mesh placed by the node hierarchy (node
// transforms, the file's unit and up applied), materials (albedo from the base or diffuse colour,
// emission from the emissive colour, double-sidedness) and punctual lights. The units of lights
// (docs/scene-format.md): glTF's candela (point, spot) and lux (directional) are taken one to one as
// radiant intensity and irradiance; emission (emissiveFactor x KHR_materials_emissive_strength, in
// nits) as radiance; spot cone half-angles become full angles. What cannot be baked is noted.
#include "bake/scene_import.h"
#include "bake/scene_import_gltf.h"
#include "bake/scene_import_log.h"

#include "core/error.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>

namespace tetprobe {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail_at(const std::string& where, const std::string& what) {
    throw Error(Status::scene, where + ": " + what);
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string rgb(const std::array<float, 3>& c) {
    return "(" + number(c[0]) + ", " + number(c[1]) + ", " + number(c[2]) + ")";
}

// Every file Assimp opens goes through here, so a file the scene refers to that cannot be read (a
// glTF's .bin, an OBJ's .mtl) is an error naming it rather than a warning Assimp may only log.
class RecordingFiles : public Assimp::DefaultIOSystem {
public:
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        Assimp::IOStream* stream = Assimp::DefaultIOSystem::Open(file, mode);
        if (!stream && file) missing.push_back(file);
        return stream;
    }
    std::vector<std::string> missing;
};

// A 3x4 affine transform in double: world = linear * p + offset.
struct Affine {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    static Affine from(const aiMatrix4x4& a) {
        Affine t;
        const ai_real rows[3][4] = {{a.a1, a.a2, a.a3, a.a4}, {a.b1, a.b2, a.b3, a.b4}, {a.c1, a.c2, a.c3, a.c4}};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) t.m[r][c] = double(rows[r][c]);
        return t;
    }
    Affine then(const Affine& inner) const {  // this * inner
        Affine t;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) {
                double sum = c == 3 ? m[r][3] : 0.0;
                for (int k = 0; k < 3; ++k) sum += m[r][k] * inner.m[k][c];
                t.m[r][c] = sum;
            }
        return t;
    }
    bool identity() const {
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                if (m[r][c] != (r == c ? 1.0 : 0.0)) return false;
        return true;
    }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    void point(const aiVector3D& p, double out[3]) const {
        for (int r = 0; r < 3; ++r) out[r] = m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3];
    }
    void vector(const aiVector3D& v, double out[3]) const {
        for (int r = 0; r < 3; ++r) out[r] = m[r][0] * v.x + m[r][1] * v.y + m[r][2] * v.z;
    }
};

Affine node_to_world(const aiNode* node) {
    Affine t;
    for (; node; node = node->mParent) t = Affine::from(node->mTransformation).then(t);
    return t;
}

bool metadata_number(const aiMetadata* data, const char* key, double* out) {
    if (!data) return false;
    for (unsigned i = 0; i < data->mNumProperties; ++i) {
        if (std::string(data->mKeys[i].C_Str()) != key || !data->mValues[i].mData) continue;
        const aiMetadataEntry& e = data->mValues[i];
        switch (e.mType) {
            case AI_INT32: *out = double(*static_cast<const int32_t*>(e.mData)); return true;
            case AI_UINT64: *out = double(*static_cast<const uint64_t*>(e.mData)); return true;
            case AI_FLOAT: *out = double(*static_cast<const float*>(e.mData)); return true;
            case AI_DOUBLE: *out = *static_cast<const double*>(e.mData); return true;
            default: return false;
        }
    }
    return false;
}

std::string texture_types(const aiMaterial& material) {
    std::string names;
    for (int t = aiTextureType_DIFFUSE; t <= AI_TEXTURE_TYPE_MAX; ++t)
        if (material.GetTextureCount(aiTextureType(t)) > 0)
            names += (names.empty() ? "" : ", ") + std::string(aiTextureTypeToString(aiTextureType(t)));
    return names;
}

// One import: the file's frame, its materials converted once each, its notes.
class AssimpImport {
public:
    AssimpImport(Scene& scene, const SceneImport& request) : scene_(scene), request_(request) {}

    void run() {
        const bool gltf = request_.format == "glTF" || request_.format == "binary glTF";
        GltfFacts facts;
        if (gltf) facts = read_gltf_facts(request_.path, request_.format == "binary glTF", request_.label);

        AssimpSession session;
        Assimp::Importer importer;
        RecordingFiles* files = new RecordingFiles;  // the importer owns and deletes it
        importer.SetIOHandler(files);
        const aiScene* ai = nullptr;
        try {
            ai = importer.ReadFile(request_.path,
                                   aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
        } catch (const std::exception& e) {
            fail_at(request_.label, std::string("Assimp failed to read it: ") + e.what());
        } catch (...) {
            fail_at(request_.label, "Assimp failed to read it");
        }
        for (const std::string& missing : files->missing)
            if (missing != request_.path) fail_at(request_.label, "refers to '" + missing + "', which cannot be read");
        if (!ai) fail_at(request_.label, std::string("not a readable ") + request_.format + " file: " + importer.GetErrorString());
        if (!ai->mRootNode || (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
            fail_at(request_.label, "holds no mesh (Assimp read an incomplete scene)");
        gltf_ = gltf ? &facts : nullptr;
        ai_ = ai;

        set_frame();
        add_node(ai->mRootNode, Affine());
        if (meshes_added_ == 0)
            fail_at(request_.label, skipped_primitives_ ? "holds no triangle mesh (only points or lines)" : "holds no triangle mesh");
        add_lights();
        note_left_out();
        for (const std::string& message : session.messages()) note("Assimp: " + message);
    }

private:
    void note(const std::string& text) { scene_.add_note(request_.label + ": " + text); }

    // The file's unit and up; world = scale * turn(file coordinates).
    void set_frame() {
        double file_metres = 1.0;  // glTF: metres; OBJ: none, taken as metres
        UpAxis file_up = UpAxis::pos_y;
        double unit_cm = 0, axis = 0, sign = 0;
        if (request_.format == "FBX") {
            if (metadata_number(ai_->mMetaData, "UnitScaleFactor", &unit_cm) && unit_cm > 0 && std::isfinite(unit_cm))
                file_metres = unit_cm / 100.0;
            else
                file_metres = 0.01, note("no UnitScaleFactor: taken as centimetres");
            if (metadata_number(ai_->mMetaData, "UpAxis", &axis) && metadata_number(ai_->mMetaData, "UpAxisSign", &sign) &&
                (axis == 0 || axis == 1 || axis == 2))
                file_up = UpAxis(1 + 2 * int(axis) + (sign < 0 ? 1 : 0));
        }
        if (request_.file_up != UpAxis::file) file_up = request_.file_up;
        scale_ = request_.scale > 0 ? request_.scale : file_metres;
        world_per_metre_ = scale_ / file_metres;
        const UpAxis scene_up = request_.scene_up == UpAxis::file ? file_up : request_.scene_up;
        if (request_.scene_up == UpAxis::file) scene_.set_up(file_up);
        const AxisTurn turn = turn_between(file_up, scene_up);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) base_.m[r][c] = 0.0;
            base_.m[r][turn.from[r]] = turn.sign[r] * scale_;
        }
    }

    void add_node(const aiNode* node, const Affine& parent) {
        const Affine local = parent.then(Affine::from(node->mTransformation));
        const Affine world = base_.then(local);
        for (unsigned i = 0; i < node->mNumMeshes; ++i) add_mesh(node, ai_->mMeshes[node->mMeshes[i]], world);
        for (unsigned c = 0; c < node->mNumChildren; ++c) add_node(node->mChildren[c], local);
    }

    void add_mesh(const aiNode* node, const aiMesh* mesh, const Affine& world) {
        const std::string name = mesh->mName.length ? mesh->mName.C_Str() : "unnamed";
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || !mesh->mFaces) {
            ++skipped_primitives_;
            return;
        }
        if (mesh->mNumBones > 0) skinned_.insert(name);
        if (mesh->mNumAnimMeshes > 0) morphed_.insert(name);
        std::vector<float> vertices(3 * size_t(mesh->mNumVertices));
        const bool identity = world.identity();
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            if (identity) {
                vertices[3 * v] = mesh->mVertices[v].x, vertices[3 * v + 1] = mesh->mVertices[v].y, vertices[3 * v + 2] = mesh->mVertices[v].z;
                continue;
            }
            double p[3];
            world.point(mesh->mVertices[v], p);
            for (int a = 0; a < 3; ++a) vertices[3 * v + a] = float(p[a]);
        }
        // A mirroring transform turns counter-clockwise faces clockwise: swap two corners back.
        const bool mirrored = world.determinant() < 0;
        std::vector<uint32_t> indices;
        indices.reserve(3 * size_t(mesh->mNumFaces));
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines split off by aiProcess_SortByPType
            indices.insert(indices.end(), {face.mIndices[0], face.mIndices[mirrored ? 2 : 1], face.mIndices[mirrored ? 1 : 2]});
        }
        const std::string label = request_.label + ": node '" + node->mName.C_Str() + "', mesh '" + name + "'";
        const std::vector<Material> materials{material(mesh->mMaterialIndex, label)};
        scene_.add_mesh(vertices.data(), mesh->mNumVertices, indices.data(), indices.size() / 3, materials, nullptr, label);
        ++meshes_added_;
    }

    Material material(unsigned index, const std::string& where) {
        if (request_.material) return *request_.material;
        auto cached = materials_.find(index);
        if (cached != materials_.end()) return cached->second;
        if (index >= ai_->mNumMaterials) fail_at(where, "material " + std::to_string(index) + " is out of range");
        const aiMaterial& m = *ai_->mMaterials[index];
        aiString ai_name;
        m.Get(AI_MATKEY_NAME, ai_name);
        const std::string name = ai_name.length ? ai_name.C_Str() : "material " + std::to_string(index);
        Material out;
        if (name == AI_DEFAULT_MATERIAL_NAME) {
            note("meshes without a material take the default one (albedo " + number(out.albedo[0]) + ", one-sided)");
            return materials_[index] = out;
        }
        aiColor4D colour;
        float opacity = 1.0f;
        if (m.Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS || m.Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS) {
            out.albedo = {colour.r, colour.g, colour.b};
            if (colour.a < 1.0f) opacity = colour.a;
        }
        float ai_opacity = 1.0f;
        if (m.Get(AI_MATKEY_OPACITY, ai_opacity) == AI_SUCCESS && ai_opacity < opacity) opacity = ai_opacity;
        if (opacity < 1.0f) note("material '" + name + "' is partly transparent (opacity " + number(opacity) + "): baked as opaque");
        const std::array<float, 3> given = out.albedo;
        for (float& a : out.albedo)
            if (a > 1.0f) a = 1.0f;
        if (out.albedo != given) note("material '" + name + "': albedo " + rgb(given) + " clamped to " + rgb(out.albedo));
        if (m.Get(AI_MATKEY_COLOR_EMISSIVE, colour) == AI_SUCCESS) {
            double strength = 1.0;
            if (gltf_ && index < gltf_->emissive_strength.size()) strength = gltf_->emissive_strength[index];
            out.emission = {float(colour.r * strength), float(colour.g * strength), float(colour.b * strength)};
        }
        int two_sided = 0;
        if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) out.two_sided = two_sided != 0;
        const std::string textures = texture_types(m);
        if (!textures.empty())
            note("material '" + name + "' has textures (" + textures + "), which are not baked: its colours are used (albedo " +
                 rgb(out.albedo) + ", emission " + rgb(out.emission) + ")");
        validate_material(out, where + ", material '" + name + "'");
        return materials_[index] = out;
    }

    void add_lights() {
        std::set<std::string> moded;
        size_t placed = 0;
        for (unsigned i = 0; i < ai_->mNumLights; ++i) {
            const aiLight& light = *ai_->mLights[i];
            const std::string name = light.mName.C_Str();
            const std::string where = request_.label + ": light '" + name + "'";
            LightDescription d;
            switch (light.mType) {
                case aiLightSource_DIRECTIONAL: d.type = LightType::directional; break;
                case aiLightSource_POINT: d.type = LightType::point; break;
                case aiLightSource_SPOT: d.type = LightType::spot; break;
                case aiLightSource_AREA: note("light '" + name + "' is an area light: left out (only directional, point and spot lights are baked)"); continue;
                case aiLightSource_AMBIENT: note("light '" + name + "' is an ambient light: left out (give the JSON scene a sky instead)"); continue;
                default: note("light '" + name + "' is of a kind Assimp cannot represent (an area or volume light): left out"); continue;
            }
            const aiNode* node = ai_->mRootNode->FindNode(light.mName);
            if (!node) {
                note("light '" + name + "' is placed by no node: left out");
                continue;
            }
            const Affine world = base_.then(node_to_world(node));
            double position[3], direction[3];
            world.point(light.mPosition, position);
            world.vector(light.mDirection, direction);
            for (int a = 0; a < 3; ++a) d.position[a] = float(position[a]), d.direction[a] = float(direction[a]);
            // Assimp folds the file's intensity into the colour. Positional lights keep their irradiance at a
            // place when the world's unit changes: I / d^2 with d in world units.
            d.color = {light.mColorDiffuse.r, light.mColorDiffuse.g, light.mColorDiffuse.b};
            d.intensity = d.type == LightType::directional ? 1.0f : float(world_per_metre_ * world_per_metre_);
            double range = 0;
            if (metadata_number(node->mMetaData, "PBR_LightRange", &range)) d.range = float(range * scale_);
            if (d.type == LightType::spot) {
                // Assimp's cone angles are half-angles in radians (glTF's own); ours are full angles in degrees.
                d.inner_angle = float(2.0 * double(light.mAngleInnerCone) * 180.0 / kPi);
                d.outer_angle = float(2.0 * double(light.mAngleOuterCone) * 180.0 / kPi);
            }
            if (d.type != LightType::directional &&
                !(light.mAttenuationConstant == 0 && light.mAttenuationLinear == 0 && light.mAttenuationQuadratic == 1))
                note("light '" + name + "': attenuation (" + number(light.mAttenuationConstant) + ", " + number(light.mAttenuationLinear) +
                     ", " + number(light.mAttenuationQuadratic) + ") is baked as inverse-square");
            auto mode = request_.light_modes.find(name);
            if (mode != request_.light_modes.end()) {
                d.mode = mode->second;
                moded.insert(name);
            }
            scene_.add_light(d, where);
            ++placed;
        }
        for (const auto& named : request_.light_modes)
            if (!moded.count(named.first)) fail_at(request_.label, "light_modes names '" + named.first + "', which is no light of this file");
        if (gltf_ && gltf_->light_placements > placed)
            note(std::to_string(gltf_->light_placements - placed) + " of " + std::to_string(gltf_->light_placements) +
                 " nodes placing a light are left out (Assimp imports a light placed by several nodes once)");
    }

    void note_left_out() {
        if (ai_->mNumCameras) note(std::to_string(ai_->mNumCameras) + " camera(s) left out");
        if (ai_->mNumAnimations) note(std::to_string(ai_->mNumAnimations) + " animation(s) left out: the scene is baked as it stands");
        if (skipped_primitives_) note(std::to_string(skipped_primitives_) + " mesh(es) of points or lines left out");
        for (const std::string& name : skinned_) note("mesh '" + name + "' is skinned: baked in its bind pose");
        for (const std::string& name : morphed_) note("mesh '" + name + "' has morph targets: baked in its base shape");
        if (gltf_ && gltf_->scenes > 1)
            note("the file has " + std::to_string(gltf_->scenes) + " scenes: only the default one is imported");
    }

    Scene& scene_;
    const SceneImport& request_;
    const aiScene* ai_ = nullptr;
    const GltfFacts* gltf_ = nullptr;
    Affine base_;
    double scale_ = 1, world_per_metre_ = 1;
    std::map<unsigned, Material> materials_;
    size_t meshes_added_ = 0, skipped_primitives_ = 0;
    std::set<std::string> skinned_, morphed_;
};

}  // namespace

void import_assimp_file(Scene& scene, const SceneImport& import) { AssimpImport(scene, import).run(); }

}  // namespace tetprobe
