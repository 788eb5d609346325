# The documentation and the code's structure, checked so they cannot drift
# (label docs; each runs in a second or two).
#
# docs.manual: README within about 200 lines, no doc/ page over 1500, every
# relative link and anchor resolves, and no work-diary wording (numbered or
# dated rounds of work) anywhere in the tree.
add_test(NAME docs.manual
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_docs.py
          --root ${CMAKE_SOURCE_DIR})
# docs.layers: the include graph follows the layers (base, element, mesh,
# model, contact, solvers, io, driver, app): no upward edge, the solvers
# include no physics, no cycle.
add_test(NAME docs.layers
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_layers.py
          --root ${CMAKE_SOURCE_DIR})
# docs.parameter_reference: doc/parameters.md is what the declarations
# generate (coshell --print-parameters-json), and every numeric entry
# states its unit.
add_test(NAME docs.parameter_reference
  COMMAND ${COSHELL_PYTHON} ${CMAKE_SOURCE_DIR}/doc/scripts/parameter_reference.py
          --coshell $<TARGET_FILE:coshell>
          --check ${CMAKE_SOURCE_DIR}/doc/parameters.md --require-units)
set_tests_properties(docs.manual docs.layers docs.parameter_reference
  PROPERTIES LABELS "docs")
