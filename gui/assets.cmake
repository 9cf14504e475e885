# The page files of `kimp gui` and `kimp report` embedded into the binary (report/assets.h):
# gui/src plus uPlot (charts) and js-yaml (the scene editor's YAML reader) from gui/node_modules
# (installed by `npm ci --prefix gui`, scripts/install-deps.sh).
# Nothing is fetched at build or run time.
set(KIMP_GUI_DIR ${PROJECT_SOURCE_DIR}/gui)
set(KIMP_GUI_ASSET_FILES
    src/gui.js src/style.css src/gui.html src/report.html
    node_modules/uplot/dist/uPlot.iife.min.js node_modules/uplot/dist/uPlot.min.css
    node_modules/js-yaml/dist/browser/js-yaml.umd.min.js)
# The results page's script, embedded as one asset `kimp.js`: the files of gui/src/kimp/ joined in
# this order (each adds to the namespace `kimp` what the later ones use).
set(KIMP_PAGE_SCRIPT_PARTS
    src/kimp/core.js src/kimp/charts.js src/kimp/sections.js src/kimp/animation.js
    src/kimp/lumped.js src/kimp/fem.js src/kimp/results.js)
foreach(asset ${KIMP_GUI_ASSET_FILES} ${KIMP_PAGE_SCRIPT_PARTS})
  if(NOT EXISTS ${KIMP_GUI_DIR}/${asset})
    message(FATAL_ERROR "gui/${asset} is missing: run `npm ci --prefix gui` "
                        "(scripts/install-deps.sh installs uPlot and js-yaml from gui/package-lock.json)")
  endif()
endforeach()

# kimp_embed_gui_assets(OUT_VAR): adds the rule generating gui_assets.cc in the current binary
# directory and returns its path.
function(kimp_embed_gui_assets out_var)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/gui_assets.cc)
  set(deps)
  foreach(asset ${KIMP_GUI_ASSET_FILES} ${KIMP_PAGE_SCRIPT_PARTS})
    list(APPEND deps ${KIMP_GUI_DIR}/${asset})
  endforeach()
  string(REPLACE ";" "," files "${KIMP_GUI_ASSET_FILES}")
  string(REPLACE ";" "," parts "${KIMP_PAGE_SCRIPT_PARTS}")
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DROOT=${KIMP_GUI_DIR} -DFILES=${files}
            -DJOINED_NAME=kimp.js -DJOINED_PARTS=${parts}
            -P ${KIMP_GUI_DIR}/embed_assets.cmake
    DEPENDS ${deps} ${KIMP_GUI_DIR}/embed_assets.cmake
    COMMENT "Embedding the page files of kimp gui and kimp report")
  set(${out_var} ${out} PARENT_SCOPE)
endfunction()
