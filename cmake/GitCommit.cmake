# ecorail_git_commit(VAR): the abbreviated commit hash of the source tree, or "unknown" when the
# sources are not a git checkout (a tarball) or git is absent. Evaluated at configure time: a
# build tree reconfigures itself when HEAD moves, so the hash follows commits.
function(ecorail_git_commit var)
  set(hash "unknown")
  find_package(Git QUIET)
  if(GIT_FOUND AND EXISTS ${CMAKE_SOURCE_DIR}/.git)
    execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
      WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
      OUTPUT_VARIABLE out OUTPUT_STRIP_TRAILING_WHITESPACE
      RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0 AND out)
      set(hash "${out}")
    endif()
    # Reconfigure when HEAD moves (a commit or a checkout), so the hash never goes stale.
    if(EXISTS ${CMAKE_SOURCE_DIR}/.git/HEAD)
      set(watch ${CMAKE_SOURCE_DIR}/.git/HEAD)
      file(READ ${CMAKE_SOURCE_DIR}/.git/HEAD head)
      if(head MATCHES "^ref: ([^\n]+)" AND EXISTS ${CMAKE_SOURCE_DIR}/.git/${CMAKE_MATCH_1})
        list(APPEND watch ${CMAKE_SOURCE_DIR}/.git/${CMAKE_MATCH_1})
      endif()
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${watch})
    endif()
  endif()
  set(${var} "${hash}" PARENT_SCOPE)
endfunction()
