// The compute kernels, one line each: GB_KERNEL(EnumName, file_name) for kernels/file_name.comp. The one
// list: kernels/CMakeLists.txt reads it for the shaders to compile, spirv.h and spirv.cpp expand it into
// the Kernel enum, the embedded SPIR-V and the names. A stage of stepper.h records one or more of them.
GB_KERNEL(TriangleGeometry, triangle_geometry)
GB_KERNEL(VertexGeometry, vertex_geometry)
GB_KERNEL(TriangleVolume, triangle_volume)
GB_KERNEL(TreeSum, tree_sum)
GB_KERNEL(FilmState, film_state)
GB_KERNEL(AirInflow, air_inflow)
GB_KERNEL(AirTransfer, air_transfer)
GB_KERNEL(Forces, forces)
GB_KERNEL(Integrate, integrate)
GB_KERNEL(ExternalForces, external_forces)
GB_KERNEL(ImplicitPredict, implicit_predict)
GB_KERNEL(VertexBlockDescent, vertex_block_descent)
GB_KERNEL(ImplicitVelocity, implicit_velocity)
GB_KERNEL(DrainageOutflow, drainage_outflow)
GB_KERNEL(DrainageGather, drainage_gather)
