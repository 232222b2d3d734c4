"""Every model's kernels behind one signature, selected by the model index (sorted names).

GENERATED FILE: DO NOT EDIT.
Source: derive/codegen/dispatch.py (from the model table)
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import numba as nb
import numpy as np

from . import ct3, cv3, se3r6, se3se3

MODEL_NAMES = ('ct3', 'cv3', 'se3r6', 'se3se3')
N_TANGENT = np.array([7, 6, 12, 12])
N_INTERNAL = np.array([7, 6, 18, 27])
#: COMMON_MISSING[model, k] = 1.0 where the model carries no information on common coordinate k (common_missing)
COMMON_MISSING = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])


@nb.njit(cache=True, inline="always")
def predict(model, s, p, dt, q):
    if model == 0:
        ct3.predict(s, p, dt, q[0], q[1], q[2])
    elif model == 1:
        cv3.predict(s, p, dt, q[0])
    elif model == 2:
        se3r6.predict(s, p, dt, q[0], q[1])
    elif model == 3:
        se3se3.predict(s, p, dt, q[0], q[1])


@nb.njit(cache=True, inline="always")
def update_pose3(model, s, p, z, r):
    if model == 2:
        return se3r6.update_pose3(s, p, z[0], z[1], z[2], z[3], z[4], z[5], r[0], r[1])
    elif model == 3:
        return se3se3.update_pose3(s, p, z[0], z[1], z[2], z[3], z[4], z[5], r[0], r[1])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def calH_pose3(model, s):
    if model == 2:
        return se3r6.calH_pose3(s)
    elif model == 3:
        return se3se3.calH_pose3(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def innovation_logdet_pose3(model, s, p, r):
    if model == 2:
        return se3r6.innovation_logdet_pose3(s, p, r[0], r[1])
    elif model == 3:
        return se3se3.innovation_logdet_pose3(s, p, r[0], r[1])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def update_position3(model, s, p, z, r):
    if model == 0:
        return ct3.update_position3(s, p, z[0], z[1], z[2], r[0])
    elif model == 1:
        return cv3.update_position3(s, p, z[0], z[1], z[2], r[0])
    elif model == 2:
        return se3r6.update_position3(s, p, z[0], z[1], z[2], r[0])
    elif model == 3:
        return se3se3.update_position3(s, p, z[0], z[1], z[2], r[0])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def calH_position3(model, s):
    if model == 0:
        return ct3.calH_position3(s)
    elif model == 1:
        return cv3.calH_position3(s)
    elif model == 2:
        return se3r6.calH_position3(s)
    elif model == 3:
        return se3se3.calH_position3(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def innovation_logdet_position3(model, s, p, r):
    if model == 0:
        return ct3.innovation_logdet_position3(s, p, r[0])
    elif model == 1:
        return cv3.innovation_logdet_position3(s, p, r[0])
    elif model == 2:
        return se3r6.innovation_logdet_position3(s, p, r[0])
    elif model == 3:
        return se3se3.innovation_logdet_position3(s, p, r[0])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def state_from_physical(model, x):
    if model == 0:
        return ct3.state_from_physical(x)
    elif model == 1:
        return cv3.state_from_physical(x)
    elif model == 2:
        return se3r6.state_from_physical(x)
    elif model == 3:
        return se3se3.state_from_physical(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def state_to_physical(model, s):
    if model == 0:
        return ct3.state_to_physical(s)
    elif model == 1:
        return cv3.state_to_physical(s)
    elif model == 2:
        return se3r6.state_to_physical(s)
    elif model == 3:
        return se3se3.state_to_physical(s)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def physical_to_common(model, x):
    if model == 0:
        return ct3.physical_to_common(x)
    elif model == 1:
        return cv3.physical_to_common(x)
    elif model == 2:
        return se3r6.physical_to_common(x)
    elif model == 3:
        return se3se3.physical_to_common(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def physical_to_common_jacobian(model, x):
    if model == 0:
        return ct3.physical_to_common_jacobian(x)
    elif model == 1:
        return cv3.physical_to_common_jacobian(x)
    elif model == 2:
        return se3r6.physical_to_common_jacobian(x)
    elif model == 3:
        return se3se3.physical_to_common_jacobian(x)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_to_state(model, c):
    if model == 0:
        return ct3.common_to_state(c)
    elif model == 1:
        return cv3.common_to_state(c)
    elif model == 2:
        return se3r6.common_to_state(c)
    elif model == 3:
        return se3se3.common_to_state(c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_jacobian(model, c):
    if model == 0:
        return ct3.common_jacobian(c)
    elif model == 1:
        return cv3.common_jacobian(c)
    elif model == 2:
        return se3r6.common_jacobian(c)
    elif model == 3:
        return se3se3.common_jacobian(c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_missing(model):
    if model == 0:
        return ct3.common_missing()
    elif model == 1:
        return cv3.common_missing()
    elif model == 2:
        return se3r6.common_missing()
    elif model == 3:
        return se3se3.common_missing()
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def between(model, s, t):
    if model == 0:
        return ct3.between(s, t)
    elif model == 1:
        return cv3.between(s, t)
    elif model == 2:
        return se3r6.between(s, t)
    elif model == 3:
        return se3se3.between(s, t)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def right_jacobian_inv(model, eps):
    if model == 0:
        return ct3.right_jacobian_inv(eps)
    elif model == 1:
        return cv3.right_jacobian_inv(eps)
    elif model == 2:
        return se3r6.right_jacobian_inv(eps)
    elif model == 3:
        return se3se3.right_jacobian_inv(eps)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def tangent_error(model, s, c):
    if model == 0:
        return ct3.tangent_error(s, c)
    elif model == 1:
        return cv3.tangent_error(s, c)
    elif model == 2:
        return se3r6.tangent_error(s, c)
    elif model == 3:
        return se3se3.tangent_error(s, c)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def retract(model, s, eps):
    if model == 0:
        ct3.retract(s, eps)
    elif model == 1:
        cv3.retract(s, eps)
    elif model == 2:
        se3r6.retract(s, eps)
    elif model == 3:
        se3se3.retract(s, eps)


@nb.njit(cache=True, inline="always")
def common_of_state(model, s, p, c, Pc):
    if model == 0:
        ct3.common_of_state(s, p, c, Pc)
    elif model == 1:
        cv3.common_of_state(s, p, c, Pc)
    elif model == 2:
        se3r6.common_of_state(s, p, c, Pc)
    elif model == 3:
        se3se3.common_of_state(s, p, c, Pc)


@nb.njit(cache=True, inline="always")
def state_of_common(model, c, Pc, s, p):
    if model == 0:
        ct3.state_of_common(c, Pc, s, p)
    elif model == 1:
        cv3.state_of_common(c, Pc, s, p)
    elif model == 2:
        se3r6.state_of_common(c, Pc, s, p)
    elif model == 3:
        se3se3.state_of_common(c, Pc, s, p)


@nb.njit(cache=True, inline="always")
def between_add(model, s, t, w, acc):
    if model == 0:
        ct3.between_add(s, t, w, acc)
    elif model == 1:
        cv3.between_add(s, t, w, acc)
    elif model == 2:
        se3r6.between_add(s, t, w, acc)
    elif model == 3:
        se3se3.between_add(s, t, w, acc)


@nb.njit(cache=True, inline="always")
def mix_transport(model, s, t, pt, w, acc):
    if model == 0:
        ct3.mix_transport(s, t, pt, w, acc)
    elif model == 1:
        cv3.mix_transport(s, t, pt, w, acc)
    elif model == 2:
        se3r6.mix_transport(s, t, pt, w, acc)
    elif model == 3:
        se3se3.mix_transport(s, t, pt, w, acc)


@nb.njit(cache=True, inline="always")
def state_from_physical_into(model, x, out):
    if model == 0:
        ct3.state_from_physical_into(x, out)
    elif model == 1:
        cv3.state_from_physical_into(x, out)
    elif model == 2:
        se3r6.state_from_physical_into(x, out)
    elif model == 3:
        se3se3.state_from_physical_into(x, out)


@nb.njit(cache=True, inline="always")
def between_into(model, s, t, out):
    if model == 0:
        ct3.between_into(s, t, out)
    elif model == 1:
        cv3.between_into(s, t, out)
    elif model == 2:
        se3r6.between_into(s, t, out)
    elif model == 3:
        se3se3.between_into(s, t, out)


@nb.njit(cache=True, inline="always")
def right_jacobian_inv_into(model, eps, out):
    if model == 0:
        ct3.right_jacobian_inv_into(eps, out)
    elif model == 1:
        cv3.right_jacobian_inv_into(eps, out)
    elif model == 2:
        se3r6.right_jacobian_inv_into(eps, out)
    elif model == 3:
        se3se3.right_jacobian_inv_into(eps, out)


@nb.njit(cache=True, inline="always")
def common_to_state_into(model, c, out):
    if model == 0:
        ct3.common_to_state_into(c, out)
    elif model == 1:
        cv3.common_to_state_into(c, out)
    elif model == 2:
        se3r6.common_to_state_into(c, out)
    elif model == 3:
        se3se3.common_to_state_into(c, out)


@nb.njit(cache=True, inline="always")
def common_jacobian_into(model, c, out):
    if model == 0:
        ct3.common_jacobian_into(c, out)
    elif model == 1:
        cv3.common_jacobian_into(c, out)
    elif model == 2:
        se3r6.common_jacobian_into(c, out)
    elif model == 3:
        se3se3.common_jacobian_into(c, out)


@nb.njit(cache=True, inline="always")
def physical_to_common_into(model, x, out):
    if model == 0:
        ct3.physical_to_common_into(x, out)
    elif model == 1:
        cv3.physical_to_common_into(x, out)
    elif model == 2:
        se3r6.physical_to_common_into(x, out)
    elif model == 3:
        se3se3.physical_to_common_into(x, out)


@nb.njit(cache=True, inline="always")
def physical_to_common_jacobian_into(model, x, out):
    if model == 0:
        ct3.physical_to_common_jacobian_into(x, out)
    elif model == 1:
        cv3.physical_to_common_jacobian_into(x, out)
    elif model == 2:
        se3r6.physical_to_common_jacobian_into(x, out)
    elif model == 3:
        se3se3.physical_to_common_jacobian_into(x, out)


@nb.njit(cache=True, inline="always")
def physical_into(model, s, out):
    if model == 0:
        ct3.physical_into(s, out)
    elif model == 1:
        cv3.physical_into(s, out)
    elif model == 2:
        se3r6.physical_into(s, out)
    elif model == 3:
        se3se3.physical_into(s, out)


@nb.njit(cache=True, inline="always")
def calH_pose3_into(model, s, out):
    if model == 2:
        se3r6.calH_pose3_into(s, out)
    elif model == 3:
        se3se3.calH_pose3_into(s, out)


@nb.njit(cache=True, inline="always")
def calH_position3_into(model, s, out):
    if model == 0:
        ct3.calH_position3_into(s, out)
    elif model == 1:
        cv3.calH_position3_into(s, out)
    elif model == 2:
        se3r6.calH_position3_into(s, out)
    elif model == 3:
        se3se3.calH_position3_into(s, out)


@nb.njit(cache=True, inline="always")
def between_add_at(model, ws, js, jt, w, jacc):
    if model == 0:
        ct3.between_add_at(ws, js, jt, w, jacc)
    elif model == 1:
        cv3.between_add_at(ws, js, jt, w, jacc)
    elif model == 2:
        se3r6.between_add_at(ws, js, jt, w, jacc)
    elif model == 3:
        se3se3.between_add_at(ws, js, jt, w, jacc)


@nb.njit(cache=True, inline="always")
def mix_transport_at(model, ws, js, jt, jpt, w, jacc):
    if model == 0:
        ct3.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 1:
        cv3.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 2:
        se3r6.mix_transport_at(ws, js, jt, jpt, w, jacc)
    elif model == 3:
        se3se3.mix_transport_at(ws, js, jt, jpt, w, jacc)


@nb.njit(cache=True, inline="always")
def retract_at(model, ws, js, jeps):
    if model == 0:
        ct3.retract_at(ws, js, jeps)
    elif model == 1:
        cv3.retract_at(ws, js, jeps)
    elif model == 2:
        se3r6.retract_at(ws, js, jeps)
    elif model == 3:
        se3se3.retract_at(ws, js, jeps)


@nb.njit(cache=True, inline="always")
def mix_on_group_at(model, ws, M, rw, rs, rp, rS, rPp, rd):
    if model == 0:
        return ct3.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 1:
        return cv3.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 2:
        return se3r6.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    elif model == 3:
        return se3se3.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def common_of_state_at(model, ws, js, jp, jc, jPc):
    if model == 0:
        ct3.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 1:
        cv3.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 2:
        se3r6.common_of_state_at(ws, js, jp, jc, jPc)
    elif model == 3:
        se3se3.common_of_state_at(ws, js, jp, jc, jPc)


@nb.njit(cache=True, inline="always")
def state_of_common_at(model, ws, jc, jPc, js, jp):
    if model == 0:
        ct3.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 1:
        cv3.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 2:
        se3r6.state_of_common_at(ws, jc, jPc, js, jp)
    elif model == 3:
        se3se3.state_of_common_at(ws, jc, jPc, js, jp)


@nb.njit(cache=True, inline="always")
def step_ll_pose3(model, ws, js, jp, dt, jq, jz, jr):
    if model == 2:
        return se3r6.step_ll_pose3(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jz, 3], ws[jz, 4], ws[jz, 5], ws[jr, 0], ws[jr, 1])
    elif model == 3:
        return se3se3.step_ll_pose3(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jz, 3], ws[jz, 4], ws[jz, 5], ws[jr, 0], ws[jr, 1])
    raise ValueError('dispatch: model index out of range')


@nb.njit(cache=True, inline="always")
def step_ll_position3(model, ws, js, jp, dt, jq, jz, jr):
    if model == 0:
        return ct3.step_ll_position3(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jq, 2], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0])
    elif model == 1:
        return cv3.step_ll_position3(ws, js, jp, dt, ws[jq, 0], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0])
    elif model == 2:
        return se3r6.step_ll_position3(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0])
    elif model == 3:
        return se3se3.step_ll_position3(ws, js, jp, dt, ws[jq, 0], ws[jq, 1], ws[jz, 0], ws[jz, 1], ws[jz, 2], ws[jr, 0])
    raise ValueError('dispatch: model index out of range')
