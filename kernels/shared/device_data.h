// The data of the Vulkan stepper: the storage buffers of descriptor set 0, one line each in binding order, and the
// per-particle arrays of State they hold. The one list (an X-macro file like kernel_list.h, read as C++ and as
// GLSL): it makes State's arrays (cpu-reference/model/state.h), the binding numbers (GB_BINDING_<NAME>, shared_step.h),
// the GLSL declarations (common.glsl) and the Vulkan stepper's buffers, uploads and read-backs
// (host/vulkan_stepper.cpp). An includer defines the three macros, includes this file and undefines them.
//
// GB_BUFFER(binding, NAME, element, declarator, access): a buffer that is not one of State's per-particle arrays.
// GB_PARTICLE_ARRAY(binding, NAME, name, components, element, access, transfer, created): a buffer holding one
//   per-particle array of State, called `name` on both sides: components 3 is a Vec3Array, stored as its x, y and
//   z blocks of `particles` elements (LOAD3/STORE3); `created` is a new particle's value (State::append).
// GB_PARTICLE_BLOCK(NAME, block, name, components, transfer, created): a per-particle float array of State kept in
//   buffer NAME from block `block` (of `particles` floats) on, beside the others there (lavapipe allows 32 storage
//   buffers a stage); components 3 is a Vec3Array in blocks block, block + 1 and block + 2.
//
// access (GLSL): readonly, or GB_WRITABLE where some stage writes it.
// transfer (host): ReadBack: load() uploads it and store() brings it back; UploadOnly: load() uploads it, the
//   device only reads it or uses it as scratch; WithMesh: uploaded with the mesh (load() and updateTopology()).

GB_BUFFER(0, PARAMS, Params, params, readonly)             // the parameter block (shared_params.h)
GB_BUFFER(1, STEPS, StepUniformsBlock, steps[], readonly)  // one StepUniformsBlock per step of a batch
GB_PARTICLE_ARRAY(2, POSITION, position, 3, float, GB_WRITABLE, ReadBack, 0)  // x_i (m)
GB_PARTICLE_ARRAY(3, VELOCITY, velocity, 3, float, GB_WRITABLE, ReadBack, 0)  // v_i (m/s)
// The explicit forces of the step (implicit integrator), or the total force of Eq. (2) (explicit) (N).
GB_PARTICLE_ARRAY(4, FORCE, force, 3, float, GB_WRITABLE, ReadBack, 0)
GB_PARTICLE_ARRAY(5, NORMAL, normal, 3, float, GB_WRITABLE, ReadBack, 0)                // unit vertex normal n_i
GB_PARTICLE_ARRAY(6, AIR_INFLOW, airInflow, 3, float, GB_WRITABLE, ReadBack, 0)         // Eq. (5) (m^3/s)
GB_PARTICLE_ARRAY(7, AIR_FLOW, airFlow, 3, float, GB_WRITABLE, ReadBack, 0)             // Eqs. (7)-(8), the front
GB_PARTICLE_ARRAY(8, AIR_FLOW_NEXT, airFlowNext, 3, float, GB_WRITABLE, UploadOnly, 0)  // the Jacobi back buffer
GB_PARTICLE_ARRAY(9, MASS, mass, 1, float, readonly, UploadOnly, 0)                     // m_i (kg), fixed at creation
// Liquid carried by the particle (m^3): w_e of Section 5.1.
GB_PARTICLE_ARRAY(10, LIQUID, liquid, 1, float, GB_WRITABLE, ReadBack, 0)
GB_PARTICLE_ARRAY(11, VORONOI_AREA, voronoiArea, 1, float, GB_WRITABLE, ReadBack, 0)  // mixed A_Vor(p_i) (m^2)
GB_PARTICLE_ARRAY(12, THICKNESS, thickness, 1, float, GB_WRITABLE, ReadBack, 0)       // e_i = liquid / A_Vor (m)
// E_i of Eq. (4) (N/m); the physical tension model keeps its tension 2 gamma here.
GB_PARTICLE_ARRAY(13, ELASTICITY, elasticity, 1, float, GB_WRITABLE, ReadBack, 0)
GB_PARTICLE_ARRAY(14, LIFETIME, lifetime, 1, float, GB_WRITABLE, ReadBack, 0)  // time since creation (s)
// Wire-frame coordinate of an end particle (wire_frame.h); negative: pinned where it is (fixed rings).
GB_PARTICLE_ARRAY(15, WIRE_PARAM, wireParam, 1, float, readonly, UploadOnly, 0)
// 1 while the particle exists: a removed particle is flagged dead, never renumbered.
GB_PARTICLE_ARRAY(16, ALIVE, alive, 1, uint, readonly, WithMesh, 1)
GB_BUFFER(17, TRIANGLES, uint, triangles[], readonly)               // Topology::triangles
GB_BUFFER(18, REST_LENGTH, float, restLength[], GB_WRITABLE)        // Topology::restLength (film_rest_lengths)
GB_BUFFER(19, SPRING_OFFSET, uint, springOffset[], readonly)        // Topology::springOffset (CSR)
GB_BUFFER(20, SPRING_INDEX, uint, springIndex[], readonly)          // Topology::springIndex
GB_BUFFER(21, SPRING_NEIGHBOUR, uint, springNeighbour[], readonly)  // Topology::springNeighbour
GB_BUFFER(22, TRIANGLE_OFFSET, uint, triangleOffset[], readonly)    // Topology::triangleOffset (CSR)
GB_BUFFER(23, TRIANGLE_CORNER, uint, triangleCorner[], readonly)    // Topology::triangleCorner: corners 3 t + c
GB_BUFFER(24, BOUNDARY, uint, boundary[], readonly)                 // Topology::boundary: the end particles
// The stages' sums: the volume's tree sum, the coarse correction's patch system, the energy budget's terms and
// slots, one region after the other (reduce regions, shared_step.h).
GB_BUFFER(25, REDUCE, float, reduce[], GB_WRITABLE)
// The liquid's arrays: the paper's drainage passes and the film flow's state and scratch, below.
GB_BUFFER(26, DRAINAGE, float, drainage[], GB_WRITABLE)
GB_PARTICLE_BLOCK(DRAINAGE, 0, drainOutflow, 1, ReadBack, 0)  // liquid particle i sends downhill (m^3), drainage pass 1
GB_PARTICLE_BLOCK(DRAINAGE, 1, drainWeight, 1, ReadBack, 0)   // sum of d_dir of Eq. (14) over i's neighbours, pass 1
// Film flow (docs/model.md "Film flow"): the liquid's depth-averaged velocity relative to the film's surface, tangent
// to it (m/s), and the surfactant per liquid, relative to a new film's (Gamma / Gamma_0 = surfactant e / e_0).
GB_PARTICLE_BLOCK(DRAINAGE, 2, flowVelocity, 3, ReadBack, 0)
GB_PARTICLE_BLOCK(DRAINAGE, 5, surfactant, 1, ReadBack, 1)
// Film flow scratch: the new velocity (pass 1), the share of its outflow a particle can give (pass 2, 1: all) and the
// surfactant at the start of the flow (pass 2), which the gathers of pass 3 read while particles write theirs.
GB_PARTICLE_BLOCK(DRAINAGE, 6, flowVelocityNext, 3, UploadOnly, 0)
GB_PARTICLE_BLOCK(DRAINAGE, 9, flowLimit, 1, UploadOnly, 0)
GB_PARTICLE_BLOCK(DRAINAGE, 10, surfactantBefore, 1, UploadOnly, 0)
// The particle's area per spring, A_i / k_i (pass 1), which every swept area of passes 2 and 3 reads
// (filmFlowSweptArea).
GB_PARTICLE_BLOCK(DRAINAGE, 11, flowAreaShare, 1, UploadOnly, 0)
// Per triangle, written by the geometry stage's first pass and gathered by its second (State::triangleNormal,
// State::cornerArea): (x1 - x0) x (x2 - x0) as x, y and z blocks of `triangles` floats; each corner's Voronoi area.
GB_BUFFER(27, TRIANGLE_NORMAL, float, triangleNormal[], GB_WRITABLE)
GB_BUFFER(28, CORNER_AREA, float, cornerArea[], GB_WRITABLE)
GB_BUFFER(29, CONTACTS, uint, contacts[],
          GB_WRITABLE)  // Topology::contacts, then the device search's regions (shared_step.h)
GB_PARTICLE_ARRAY(30, PREVIOUS_POSITION, previousPosition, 3, float, GB_WRITABLE, ReadBack, 0)  // x_t of a step
// The implicit solver's lists: its particles colour by colour (Topology::colourOrder), then the coarse
// correction's patch lists (kernels/step/coarse.glsl).
GB_BUFFER(31, COLOUR_ORDER, uint, colourOrder[], readonly)
