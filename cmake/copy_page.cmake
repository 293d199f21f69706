# cmake -DSOURCE=studio/dist -DDESTINATION=BUILD/share/meander/studio -P copy_page.cmake:
# the studio's built page where `meander serve` looks for it, if it was built.
file(REMOVE_RECURSE "${DESTINATION}")
if(EXISTS "${SOURCE}/index.html")
  file(COPY "${SOURCE}/" DESTINATION "${DESTINATION}")
endif()
