# The comparisons that read the references tests/render/shared_references.h names require the test that traces
# them (per backend; it reads them from tests/references/ while those are current), so that ctest runs it first and fills the other core meanwhile instead of letting two
# comparisons start together and one wait, a core idle, for the other's trace. Names ctest does not know (a build
# without a backend) are ignored.
foreach(backend vulkan gl)
  set_tests_properties("path-traced references the comparisons share (${backend})"
    PROPERTIES FIXTURES_SETUP shared-references-${backend})
  foreach(test
      [=[GI on the Cornell box against the path tracer]=]
      [=[GI's single bounce on the Cornell box against the path tracer's]=]
      [=[GI's specular on a glossy floor against the path tracer]=]
      [=[GI around a corner of single-sided walls against the path tracer]=]
      [=[voxel cone tracing on the Cornell box against the path tracer]=]
      [=[voxel cone tracing's single bounce against the path tracer's]=]
      [=[voxel cone tracing's specular on a glossy floor against the path tracer]=]
      [=[voxel cone tracing with cones stopped by the distance field]=]
      [=[SDF GI lighting unseen surfaces from the clip-map]=]
      [=[path tracer: cornell converges]=]
      [=[foliage: the SDF GI's alpha-aware cards against built-opaque and left-out ones, and the path tracer]=]
      [=[glass: cornell-glass through voxel cone tracing against the path tracer]=]
      [=[Hybrid reflections on a mirror-like floor beat GI's specular against the path tracer]=]
      [=[Hybrid reflections on a glossy floor beat GI's specular against the path tracer]=])
    set_tests_properties("${test} (${backend})" PROPERTIES FIXTURES_REQUIRED shared-references-${backend})
  endforeach()
endforeach()
