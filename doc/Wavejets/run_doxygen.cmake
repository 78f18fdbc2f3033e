# Builds the Wavejets documentation and fails if doxygen reports any warning.
# Called by the target `wavejets_doc` (alias `doc`) and the test `wavejets_documentation`
# (doc/Wavejets/CMakeLists.txt) as
#   cmake -DDOXYGEN_EXECUTABLE=... -DWAVEJETS_SOURCE_DIR=<repository root>
#         -DWAVEJETS_DOC_OUTPUT_DIR=<output dir> [-DWAVEJETS_DOXYGEN_WARN_AS_ERROR=FAIL_ON_WARNINGS]
#         [-DWAVEJETS_MATHJAX_DIR=<MathJax 2 folder, e.g. /usr/share/javascript/mathjax>]
#         -P run_doxygen.cmake
# The HTML lands in <output dir>/html (index.html: the user manual).
cmake_minimum_required(VERSION 3.12)
foreach(var DOXYGEN_EXECUTABLE WAVEJETS_SOURCE_DIR WAVEJETS_DOC_OUTPUT_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_doxygen.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT WAVEJETS_DOXYGEN_WARN_AS_ERROR)
  set(WAVEJETS_DOXYGEN_WARN_AS_ERROR FAIL_ON_WARNINGS)
endif()
set(doc_dir "${WAVEJETS_SOURCE_DIR}/doc/Wavejets")
set(html_dir "${WAVEJETS_DOC_OUTPUT_DIR}/html")
set(WAVEJETS_DOC_WARN_LOG "${WAVEJETS_DOC_OUTPUT_DIR}/doxygen_warnings.log")

# The pictures of fig/ are copied next to the HTML pages (HTML_EXTRA_FILES), where the
# manual's <img src="..."> finds them.
file(GLOB figures "${doc_dir}/fig/*.png" "${doc_dir}/fig/*.jpg" "${doc_dir}/fig/*.svg")
list(SORT figures)
set(WAVEJETS_DOC_EXTRA_FILES "")
foreach(figure ${figures})
  string(APPEND WAVEJETS_DOC_EXTRA_FILES " \"${figure}\"")
endforeach()
# MathJax: a copy of the files the pages load, in html/mathjax (MATHJAX_RELPATH is relative to the
# pages, so the manual reads offline and can be moved), or, without a local MathJax, the CDN.
if(WAVEJETS_MATHJAX_DIR AND NOT EXISTS "${WAVEJETS_MATHJAX_DIR}/MathJax.js")
  message(WARNING "run_doxygen.cmake: no MathJax.js in WAVEJETS_MATHJAX_DIR=${WAVEJETS_MATHJAX_DIR}")
  set(WAVEJETS_MATHJAX_DIR "")
endif()
if(WAVEJETS_MATHJAX_DIR)
  set(WAVEJETS_MATHJAX_RELPATH "mathjax")
else()
  set(WAVEJETS_MATHJAX_RELPATH "https://cdn.jsdelivr.net/npm/mathjax@2")
  message(WARNING "Wavejets documentation: no local MathJax (Debian: libjs-mathjax); the pages load it from "
                  "${WAVEJETS_MATHJAX_RELPATH} and show raw TeX without a network.")
endif()
configure_file("${doc_dir}/Doxyfile.in" "${WAVEJETS_DOC_OUTPUT_DIR}/Doxyfile" @ONLY)

file(REMOVE "${WAVEJETS_DOC_WARN_LOG}")
execute_process(COMMAND "${DOXYGEN_EXECUTABLE}" "${WAVEJETS_DOC_OUTPUT_DIR}/Doxyfile"
  WORKING_DIRECTORY "${WAVEJETS_DOC_OUTPUT_DIR}"
  RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)

# The manual links the benchmark reports of the source tree; copy those that exist next to
# the HTML pages so that the links work in the generated documentation.
foreach(report results.md accuracy.md accuracy_ponca.md accuracy_ponca.png workflows.md)
  if(EXISTS "${WAVEJETS_SOURCE_DIR}/benchmark/Wavejets/${report}")
    file(COPY "${WAVEJETS_SOURCE_DIR}/benchmark/Wavejets/${report}" DESTINATION "${html_dir}/benchmark")
  endif()
endforeach()

# The MathJax 2 files that the pages load with the Doxyfile's settings (TeX input, HTML-CSS output
# with the TeX web fonts, the AMS extensions): about 2.5 MB of the package's 54 MB.
if(WAVEJETS_MATHJAX_DIR)
  set(mathjax_dir "${html_dir}/mathjax")
  file(COPY "${WAVEJETS_MATHJAX_DIR}/MathJax.js" "${WAVEJETS_MATHJAX_DIR}/extensions" DESTINATION "${mathjax_dir}")
  file(COPY "${WAVEJETS_MATHJAX_DIR}/jax/input/TeX" DESTINATION "${mathjax_dir}/jax/input")
  file(COPY "${WAVEJETS_MATHJAX_DIR}/jax/element" DESTINATION "${mathjax_dir}/jax")
  file(COPY "${WAVEJETS_MATHJAX_DIR}/jax/output/HTML-CSS" DESTINATION "${mathjax_dir}/jax/output"
       PATTERN "fonts" EXCLUDE)
  file(COPY "${WAVEJETS_MATHJAX_DIR}/jax/output/HTML-CSS/fonts/TeX"
       DESTINATION "${mathjax_dir}/jax/output/HTML-CSS/fonts")
  file(COPY "${WAVEJETS_MATHJAX_DIR}/fonts/HTML-CSS/TeX/woff" "${WAVEJETS_MATHJAX_DIR}/fonts/HTML-CSS/TeX/otf"
       DESTINATION "${mathjax_dir}/fonts/HTML-CSS/TeX")
  if(EXISTS "${WAVEJETS_MATHJAX_DIR}/localization/en")
    file(COPY "${WAVEJETS_MATHJAX_DIR}/localization/en" DESTINATION "${mathjax_dir}/localization")
  endif()
endif()

# Warnings on the sources go to the log; configuration problems go to the console.
set(warnings "")
if(EXISTS "${WAVEJETS_DOC_WARN_LOG}")
  file(READ "${WAVEJETS_DOC_WARN_LOG}" warnings)
endif()
string(STRIP "${output}\n${warnings}" report)
if(NOT report STREQUAL "")
  message("${report}")
endif()
string(REGEX MATCHALL "(warning|error):" problems "${report}")
list(LENGTH problems count)
string(STRIP "${warnings}" warnings)
if(count GREATER 0 OR NOT warnings STREQUAL "")
  message(FATAL_ERROR "doxygen reported ${count} warning(s)/error(s) (log: ${WAVEJETS_DOC_WARN_LOG})")
endif()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "doxygen failed (exit status ${status})")
endif()
message(STATUS "Wavejets documentation: ${html_dir}/index.html (0 doxygen warnings)")
