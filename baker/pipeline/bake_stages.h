#pragma once

namespace rockbake {

// Which of a bake's stages run: the command line's --no-mesh, --no-textures and --no-render,
// a library's jobs and the studio's final bake all give one, and bakeAsset applies it in one
// place. Textures and renders are made from meshes: without meshes there are neither.
struct BakeStages {
  bool mesh = true;
  bool textures = true;  // off: the preset is baked without its texture: block (presetAsBaked)
  bool render = true;

  BakeStages applied() const { return {mesh, mesh && textures, mesh && render}; }
};

}  // namespace rockbake
