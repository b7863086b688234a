/* The list of FE / continuum constitutive models (an X-macro, as libCEED's backend list and
 * pd/materials.h): a new model is one file fem/material_<id>.c defining
 * pf_fem_material_<id>, and one line here. The id is the deck's `model:` name. */
PF_FEM_MATERIAL(elastic)
PF_FEM_MATERIAL(neo_hookean)
PF_FEM_MATERIAL(j2)
PF_FEM_MATERIAL(johnson_cook)
PF_FEM_MATERIAL(modified_johnson_cook)
