# cmake -DBUILD_DIR=… -DTARGET=… -DEXPECT=fails|compiles -DREASON=regex -P expect_compile.cmake
# Builds one case of tests/build; a case that must fail passes only when its
# build fails with output matching REASON.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(EXPECT STREQUAL "compiles")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${TARGET} must compile and did not:\n${out}")
  endif()
  message(STATUS "${TARGET} compiles, as it must")
elseif(code EQUAL 0)
  message(FATAL_ERROR "${TARGET} must not compile, and it did")
elseif(NOT out MATCHES "${REASON}")
  message(FATAL_ERROR "${TARGET} failed to compile, but not because of '${REASON}':\n${out}")
else()
  message(STATUS "${TARGET} does not compile (${REASON}), as it must not")
endif()
