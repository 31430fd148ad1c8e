#include "pipeline/export_meshes.h"

#include <stdexcept>

#include <spdlog/spdlog.h>
#include <tbb/task_group.h>

#include "export/glb_file.h"
#include "export/obj_file.h"
#include "export/ply_file.h"
#include "pipeline/delivery_profile.h"
#include "platform/stopwatch.h"

namespace rockbake {

MaterialMaps lodMaterialMaps(const TextureSet& textures, int lod) {
  const auto uri = [&](int at, TextureMap map) {
    const TextureFile* f = findTextureFile(textures, at, map);
    return f ? std::string(kTextureFolder) + "/" + f->file : std::string();
  };
  return {uri(lod, TextureMap::BaseColor), uri(lod, TextureMap::Normal), uri(lod, TextureMap::Orm),
          uri(0, TextureMap::Height)};
}

double exportMeshes(const MeshStageResult& r, const TextureSet* textures, const Preset& preset,
                    const std::filesystem::path& asset_dir, const ClastSet* clasts) {
  const Stopwatch export_clock;
  const AssetMeshes& meshes = r.meshes;
  const DeliveryConventions delivery = deliveryConventions(preset, asset_dir);
  if (textures && textures->lods.size() != 1 + r.lods.size())
    throw std::logic_error("exportMeshes: the texture set has " + std::to_string(textures->lods.size()) + " LODs for " +
                           std::to_string(1 + r.lods.size()));
  // The files are independent: write them concurrently, so one file's
  // formatting overlaps another's disk writes and fsync.
  const auto timed = [&](const char* what, auto&& write) {
    return [&, what, write] {
      Stopwatch clock;
      write();
      spdlog::debug("{}: {} in {:.3f} s", preset.name, what, clock.lap());
    };
  };
  tbb::task_group exports;
  if (exportsFormat(preset, "ply")) {
    exports.run(timed("rock.ply", [&] { writePly(meshes.rock, asset_dir / "rock.ply"); }));
    if (!meshes.colluvium.positions.empty()) {
      exports.run(timed("colluvium.ply", [&] { writePly(meshes.colluvium, asset_dir / "colluvium.ply"); }));
    } else {
      std::error_code ignored;  // no colluvium: no stale file from an earlier bake either
      std::filesystem::remove(asset_dir / "colluvium.ply", ignored);
    }
  }
  if (exportsFormat(preset, "obj"))
    exports.run(timed("obj", [&] {
      if (textures)
        writeObj(meshes, asset_dir / "rock.obj", &textures->lods[0], lodMaterialMaps(*textures, 0));
      else
        writeObj(meshes, asset_dir / "rock.obj");
    }));
  if (exportsFormat(preset, "glb"))
    for (std::size_t i = 0; i <= r.lods.size(); ++i)
      exports.run(timed(i == 0 ? "glb" : "lod", [&, i] {
        const AssetMeshes& lod = textures ? textures->lods[i] : i == 0 ? meshes : r.lods[i - 1];
        writeGlb(lod, asset_dir / r.lod_files[i], int(i),
                 textures ? lodMaterialMaps(*textures, int(i)) : MaterialMaps{},
                 clasts && !clasts->stones.empty() ? clasts : nullptr, delivery.glb);
      }));
  exports.wait();  // rethrows the first failure
  return export_clock.elapsed();
}

}  // namespace rockbake
