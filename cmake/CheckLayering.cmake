# Checks that every #include of a room's files names only rooms that room may use
# (cmake/EcorailRooms.cmake writes the rules: a room's own name and the rooms below it).
# Included at configure time, it leaves the violations in ECORAIL_LAYERING_VIOLATIONS; run as a
# script (the test `layering_includes`) it prints them and fails:
#   cmake -DECORAIL_SOURCE_DIR=<source> -DECORAIL_RULES=<build>/generated/layering_rules.cmake
#         -P cmake/CheckLayering.cmake
# A violation is an include "<room>/..." or <room>/... of a room not allowed, or a relative
# include that climbs out of the directory ("../"), which would hide the room it reaches.

cmake_minimum_required(VERSION 3.22)
include(${ECORAIL_RULES})
set(ECORAIL_LAYERING_VIOLATIONS "")
foreach(dir ${ECORAIL_CHECKED_DIRS})
  file(GLOB_RECURSE files ${ECORAIL_SOURCE_DIR}/${dir}/*.hpp ${ECORAIL_SOURCE_DIR}/${dir}/*.h
    ${ECORAIL_SOURCE_DIR}/${dir}/*.cpp ${ECORAIL_SOURCE_DIR}/${dir}/*.cc)
  foreach(file ${files})
    file(STRINGS ${file} includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    file(RELATIVE_PATH shown ${ECORAIL_SOURCE_DIR} ${file})
    foreach(line ${includes})
      if(line MATCHES "#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"]")
        set(path ${CMAKE_MATCH_1})
        if(path MATCHES "^\\.\\./")
          string(APPEND ECORAIL_LAYERING_VIOLATIONS
            "  ${shown}: #include \"${path}\" climbs out of ${dir}/ (name the room instead)\n")
        elseif(path MATCHES "^([A-Za-z_]+)/")
          set(target_room ${CMAKE_MATCH_1})
          if(target_room IN_LIST ECORAIL_ROOMS OR target_room IN_LIST ECORAIL_CHECKED_DIRS)
            if(NOT target_room IN_LIST ECORAIL_ALLOWED_${dir})
              string(REPLACE ";" ", " allowed "${ECORAIL_ALLOWED_${dir}}")
              string(APPEND ECORAIL_LAYERING_VIOLATIONS
                "  ${shown}: #include \"${path}\": ${dir}/ may include only ${allowed}\n")
            endif()
          endif()
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

if(CMAKE_SCRIPT_MODE_FILE)
  if(ECORAIL_LAYERING_VIOLATIONS)
    message(FATAL_ERROR "An include runs up the rooms (docs/architecture.md):\n"
      "${ECORAIL_LAYERING_VIOLATIONS}")
  endif()
  list(LENGTH ECORAIL_CHECKED_DIRS n)
  message(STATUS "layering: the includes of ${n} directories keep to their rooms")
endif()
