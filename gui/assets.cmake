# The page files of `kimp gui` and `kimp report` embedded into the binary (report/assets.h):
# gui/src plus uPlot (charts) and js-yaml (the scene editor's YAML reader) from gui/node_modules
# (installed by `npm ci --prefix gui`, scripts/install-deps.sh).
# Nothing is fetched at build or run time.
set(KIMP_GUI_DIR ${PROJECT_SOURCE_DIR}/gui)
set(KIMP_GUI_ASSET_FILES
    src/style.css src/gui.html src/report.html
    node_modules/uplot/dist/uPlot.iife.min.js node_modules/uplot/dist/uPlot.min.css
    node_modules/js-yaml/dist/browser/js-yaml.umd.min.js)
# The shipped scenes (data/scenes), the GUI's examples menu (GET /api/examples, /assets/NAME.yaml).
file(GLOB KIMP_GUI_EXAMPLE_SCENES CONFIGURE_DEPENDS RELATIVE ${KIMP_GUI_DIR} ${PROJECT_SOURCE_DIR}/data/scenes/*.yaml)
list(APPEND KIMP_GUI_ASSET_FILES ${KIMP_GUI_EXAMPLE_SCENES})
# The two page scripts, each embedded as one asset <name>.js: the files of gui/src/<name>/ joined
# in this order (each adds to the script's namespace, `kimp` or `kimpGui`, what the later ones
# use). kimp.js draws results (kimp report and kimp gui), gui.js is the GUI.
set(KIMP_PAGE_SCRIPTS kimp gui)
set(KIMP_PAGE_SCRIPT_kimp core charts sections animation plan lumped fem results)
set(KIMP_PAGE_SCRIPT_gui core form runs motion parametric start)
set(KIMP_PAGE_SCRIPT_PARTS)
set(KIMP_PAGE_SCRIPT_JOINS)
foreach(script ${KIMP_PAGE_SCRIPTS})
  set(join)
  foreach(part ${KIMP_PAGE_SCRIPT_${script}})
    list(APPEND KIMP_PAGE_SCRIPT_PARTS src/${script}/${part}.js)
    list(APPEND join src/${script}/${part}.js)
  endforeach()
  string(REPLACE ";" "+" join "${join}")
  list(APPEND KIMP_PAGE_SCRIPT_JOINS "${script}.js=${join}")
endforeach()
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
  string(REPLACE ";" "," joins "${KIMP_PAGE_SCRIPT_JOINS}")
  add_custom_command(OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DROOT=${KIMP_GUI_DIR} -DFILES=${files}
            -DJOINED=${joins}
            -P ${KIMP_GUI_DIR}/embed_assets.cmake
    DEPENDS ${deps} ${KIMP_GUI_DIR}/embed_assets.cmake
    COMMENT "Embedding the page files of kimp gui and kimp report")
  set(${out_var} ${out} PARENT_SCOPE)
endfunction()
