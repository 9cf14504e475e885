# Writes OUTPUT from INPUT (base/version.cc.in) with KIMP_VERSION and the git revision of
# SOURCE_DIR, at build time; the file is rewritten only when its text changes, so an unchanged
# revision recompiles nothing. Run as: cmake -DINPUT=... -DOUTPUT=... -DSOURCE_DIR=...
# -DKIMP_VERSION=... -P write_version.cmake
execute_process(COMMAND git rev-parse --short=12 HEAD
                WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE KIMP_GIT_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT KIMP_GIT_REVISION)
  set(KIMP_GIT_REVISION "unknown")
endif()
configure_file("${INPUT}" "${OUTPUT}.new" @ONLY)
file(COPY_FILE "${OUTPUT}.new" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.new")
