/* The list of contact methods (an X-macro, as pd/materials.h): a new method is one file
 * contact/method_<id>.c defining pf_contact_method_<id> (pf_contact_method, contact_impl.h), and
 * one line here. The order is that of the known names in messages; the first method that claims
 * a case (PD <-> PD, FE <-> PD, FE <-> FE) is that case's default. */
PF_CONTACT_METHOD(short_range)
PF_CONTACT_METHOD(surface)
PF_CONTACT_METHOD(nodes)
PF_CONTACT_METHOD(surfaces)
