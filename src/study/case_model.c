/* The model of a case (study/run.h): the case's keys as the model's plain parameters.
 * The only place where the case file's structure meets the physics. */
#include <string.h>

#include "study/run.h"

void rs_model_params_from_case(const rs_case *c, rs_model_params *p)
{
  memset(p, 0, sizeof *p);
  p->dimension = c->dimension == 3 ? 3 : 2;
  p->cells = c->cells;
  p->cells_y = c->cells_y;
  p->grid_from_range = c->grid_from_range;
  p->x_range[0] = c->x_range[0];
  p->x_range[1] = c->x_range[1];
  p->y_range[0] = c->y_range[0];
  p->y_range[1] = c->y_range[1];
  p->extent = c->extent;
  p->extent_y = c->extent_y;
  p->radius = c->radius;
  p->radius_y = c->radius_y;
  p->normal_solution = c->normal_solution;
  p->reference_length = c->reference_length;
  p->shear_modulus = c->shear_modulus;
  p->poisson_ratio = c->poisson_ratio;
  p->layer_thickness = c->layer_thickness;
  p->layer_shear_modulus = c->layer_shear_modulus;
  p->friction = c->friction;
  p->friction.mu = c->mu;
  p->plasticity = (rs_plasticity){
      .on = c->has_plasticity, .tau_c0 = c->tau_c0, .k_tau = c->k_tau, .tau_c_min = c->tau_c_min};
  /* shallow: rs_model_create copies the histories */
  p->load = c->normal_load;
  p->velocity = c->velocity;
  p->creepage = c->creepage;
  p->lateral_creepage = c->lateral_creepage;
  p->spin = c->spin;
  p->shift_velocity = c->shift_velocity;
  p->force_control = c->force_control;
  p->force = c->tangential_force;
  p->force_y = c->tangential_force_y;
  p->end_time = c->end_time;
  p->scaling = c->scaling;
  p->threads = c->threads;
  p->time_scale = c->output_interval;
}

int rs_model_from_case(rs_model *m, const rs_case *c, rs_msg *msg)
{
  rs_model_params p;
  rs_model_params_from_case(c, &p);
  return rs_model_create(m, &p, msg);
}
