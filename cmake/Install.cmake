# The build tree's data folder. The executable reads its data at
# <its folder>/../share/rockbake (baker/core/data_dir.h), so build/baker/rockbake (and
# build/tests/…, build/bench/…) read build/share/rockbake/, which links to the source
# tree's folders: an uninstalled build reads the templates and the page as they are edited.
set(ROCKBAKE_BUILD_DATA_DIR ${PROJECT_BINARY_DIR}/share/rockbake)
file(MAKE_DIRECTORY ${ROCKBAKE_BUILD_DATA_DIR})
foreach(folder render_templates studio)
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${ROCKBAKE_BUILD_DATA_DIR}/${folder} SYMBOLIC)
endforeach()
