function test_gyro_mex(source_dir)
  % gyro_mex (matlab/gyro_mex.c) in Octave: the exact step against Octave's own matrix
  % exponential of the report's equations, GyroModel's handles and geometry, SIL runs as
  % gyro_sil runs them, and every refusal an error naming what it refuses. Prints
  % "gyro_mex: all checks passed" at the end; any failed check is an error.
  check_exact_step_against_expm();
  check_exact_step_refusals();
  check_model_handles_and_geometry();
  check_model_refusals();
  check_sil_run(source_dir);
  disp('gyro_mex: all checks passed');
end

% The report's eqs 1a/1b with the torque held, x = (theta, psi, theta', psi', T1, T2):
%   J1 w1' = T1 - f w1 - H w2,  J2 w2' = T2 - f w2 + H w1
% advanced over dt by expm of the augmented matrix (torque constant: zero rows).
function x = reference_step(p, dt, states, torques)
  [j1, j2, f, h] = deal(p(1), p(2), p(3), p(4));
  a = zeros(6);
  a(1, 3) = 1;
  a(2, 4) = 1;
  a(3, 3:6) = [-f, -h, 1, 0] / j1;
  a(4, 3:6) = [h, -f, 0, 1] / j2;
  e = expm(a * dt);
  x = e(1:4, :) * [states; torques];
end

function check_exact_step_against_expm()
  p = [2.25, 2.0, 5.0, 2 * pi * 100 * 3];  % the report's gyro
  rand('seed', 29);
  n = 500;
  states = (rand(4, n) - 0.5) .* [1e-3; 1e-3; 1; 1];
  torques = (rand(2, n) - 0.5) * 400;
  for dt = [1 / 2828, 1e-2]
    ref = reference_step(p, dt, states, torques);
    [s, st] = gyro_mex('advance', p, dt, states, torques);
    assert(all(st == 0));
    assert(size(s), [4, n]);
    assert(s, ref, -1e-9);  % relative: expm's own rounding over beta dt up to 9 rad
    one = gyro_mex('advance', p, dt, states, torques(:, 1));  % one torque for all states
    assert(one, reference_step(p, dt, states, repmat(torques(:, 1), 1, n)), -1e-9);
    s32 = gyro_mex('advance', p, dt, single(states), torques);
    assert(class(s32), 'single');
    % float: within 1e-5 of each row's largest value (the angles' and the rates' scales)
    assert(max(abs(double(s32) - ref) ./ max(abs(ref), [], 2), [], 2) < 1e-5);
  end
end

function check_exact_step_refusals()
  p = [2.25, 2.0, 5.0, 1885];
  states = zeros(4, 3);
  states(3, 2) = NaN;
  [s, st] = gyro_mex('advance', p, 1e-3, states, [1; 1]);
  assert(double(st), [0, 1, 0]);
  assert(isnan(s(3, 2)));  % the refused column as it was
  expect_error(@() gyro_mex('advance', p, 1e-3, states, [1; 1]), 'gyro:non_finite_input', 'state 2');
  expect_error(@() gyro_mex('advance', p, 0, zeros(4, 1), [1; 1]), 'gyro:non_positive_step', 'advance');
  expect_error(@() gyro_mex('advance', p, 1e-3, zeros(3, 1), [1; 1]), 'gyro:wrong_size', 'states');
  expect_error(@() gyro_mex('advance', p, 1e-3, zeros(4, 2), ones(2, 3)), 'gyro:wrong_size', 'torque');
  expect_error(@() gyro_mex('advance', [1 1 1], 1e-3, zeros(4, 1), [1; 1]), 'gyro:wrong_size', 'params');
  expect_error(@() gyro_mex('warp'), 'gyro:unknown_command', 'warp');
end

% The report's sample through two models kept between calls: the one stepped moves, the other
% stays as it was; the gimbal angles are the spin axis (row 1 of ROTEG) seen from the body:
% pitch = atan2(-z, |(x, y)|), yaw = atan2(y, x).
function check_model_handles_and_geometry()
  s = gyro_mex('report_sample');
  assert(s.steps, 801);
  a = gyro_mex('model_new', s.config);
  b = gyro_mex('model_new', s.config, 'single');
  assert(a != b);
  gyro_mex('model_uncage', a, eye(3), s.body_rate);
  gyro_mex('model_uncage', b, eye(3), s.body_rate);
  dt = s.initg_step;
  turn = gyro_mex('frame_rotation', 'z', s.body_rate(2) * dt) * gyro_mex('frame_rotation', 'y', s.body_rate(1) * dt);
  body = eye(3);
  for k = 1:s.steps
    body = turn * body;
    gyro_mex('model_step_slew', a, dt, s.slew, s.spin_hz, body);
  end
  sa = gyro_mex('model_state', a);
  sb = gyro_mex('model_state', b);
  assert(sa.flags, 0);
  assert(sb.gimbal, single([0; 0]));  % untouched by a's steps
  axis = body * sa.R_earth_to_gyro(1, :)';
  assert(sa.gimbal, [atan2(-axis(3), norm(axis(1:2))); atan2(axis(2), axis(1))], 1e-12);
  assert(sa.R_earth_to_gyro * sa.R_earth_to_gyro', eye(3), 1e-14);
  assert(sa.gimbal(1) < -0.1 && sa.gimbal(2) < -0.02);
  gyro_mex('model_delete', a);
  expect_error(@() gyro_mex('model_state', a), 'gyro:not_configured', 'no such model');
  gyro_mex('model_delete', b);
end

function check_model_refusals()
  s = gyro_mex('report_sample');
  c = s.config;
  c.pitch_inertia = -1;
  expect_error(@() gyro_mex('model_new', c), 'gyro:non_positive_inertia', 'pitch_inertia = -1');
  c = s.config;
  c.errors.yaw.coulomb_friction_rad_s = -0.1;
  expect_error(@() gyro_mex('model_new', c), 'gyro:out_of_range', 'errors.yaw.coulomb_friction_rad_s');
  c = s.config;
  c.pitch_inertias = 1;
  expect_error(@() gyro_mex('model_new', c), 'gyro:unknown_field', 'pitch_inertias');
  c = s.config;
  c.torquer_axes = 'body';
  expect_error(@() gyro_mex('model_new', c), 'gyro:unknown_field', 'body');
  c.torquer_axes = 'gimbal';
  h = gyro_mex('model_new', c);
  expect_error(@() gyro_mex('model_step_slew', h, 1e-3, [0 0], 100, eye(3)), 'gyro:not_configured', 'model_step_slew');
  gyro_mex('model_uncage', h, eye(3), [0 0]);
  expect_error(@() gyro_mex('model_step_slew', h, 1e-3, [0 0], 100, 2 * eye(3)), 'gyro:invalid_rotation', 'not orthonormal');
  expect_error(@() gyro_mex('model_step_slew', h, 1e-3, [0 0], 100, eye(2)), 'gyro:wrong_size', 'R_earth_to_body');
  gyro_mex('model_delete', h);
end

% A SIL run as gyro_sil's: its columns, a row per tick, the tick in t; the scenario as text
% too; refusals naming the option or the scenario's field.
function check_sil_run(source_dir)
  path = fullfile(source_dir, 'scenarios', 'seeker_slew.json');
  [cols, tm] = gyro_mex('sil_run', path, 'precision', 'float', 'ticks', 100);
  assert(tm.precision, 'float');
  assert(tm.rows, 101);
  assert(numel(cols.t), 101);
  assert(all(isfield(cols, {'t', 'mode', 'gimbal_pitch', 'gimbal_yaw', 'flags'})));
  assert(iscellstr(cols.mode) && isa(cols.flags, 'uint64'));
  scenario = jsondecode(fileread(path));
  assert(diff(cols.t), repmat(1 / scenario.run.rate_hz, 100, 1), 1e-12);
  assert(all(ismember(tm.flags_seen_names, fieldnames(tm.counters))));
  text = strrep(fileread(path), '"duration_s": 1.5', '"duration_s": 0.02');  % 20 ticks
  [text_cols, text_tm] = gyro_mex('sil_run', text);
  assert(text_tm.rows, 21);
  assert(text_cols.gimbal_pitch(1:21), gyro_mex('sil_run', path, 'ticks', 20).gimbal_pitch);
  expect_error(@() gyro_mex('sil_run', path, 'precision', 'half'), 'gyro:out_of_range', 'precision');
  expect_error(@() gyro_mex('sil_run', path, 'speed', 2), 'gyro:unknown_field', 'speed');
  expect_error(@() gyro_mex('sil_run', path, 'ticks', 1e6, 'max_output_bytes', 1000), 'gyro:run_error', ...
               'max_output_bytes');
  bad = fullfile(source_dir, 'tests', 'data', 'bad_scenarios', 'non_physical_inertia.json');
  expect_error(@() gyro_mex('sil_run', bad), 'gyro:scenario_error', 'field:');
end

function expect_error(f, id, text)
  try
    f();
  catch e
    assert(e.identifier, id);
    assert(!isempty(strfind(e.message, text)), sprintf('"%s" not in "%s"', text, e.message));
    return;
  end
  error('test:no_error', 'expected the error %s', id);
end
