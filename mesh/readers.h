/* The mesh readers, one line each: PF_MESH_READER(name) names the ops table
 * pf_mesh_reader_<name> (mesh/mesh_impl.h) defined in mesh/<name>.c. A `file:` is given
 * to the first reader whose extension list holds its extension; `pamgen:` text goes to the
 * reader named pamgen. Include this file with PF_MESH_READER defined. */
PF_MESH_READER(gmsh)   /* .geo (meshed at start-up), .msh */
PF_MESH_READER(exodus) /* .e .exo .g .ex2 */
PF_MESH_READER(pamgen) /* inline text under pamgen: */
