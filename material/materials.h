/* The list of FE / continuum constitutive models (an X-macro, as libCEED's backend list and
 * pd/materials.h): a new model is one file material/material_<id>.c defining
 * pf_material_<id>, and one line here. The id is the deck's `model:` name. */
PF_MATERIAL(elastic)
PF_MATERIAL(neo_hookean)
PF_MATERIAL(j2)
PF_MATERIAL(johnson_cook)
PF_MATERIAL(modified_johnson_cook)
PF_MATERIAL(orthotropic)
