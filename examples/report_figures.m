function report_figures(output_dir)
  % The report's figures A-1 (gyro pitch gimbal angle) and A-2 (gyro yaw gimbal angle) from the
  % sample run (100 Hz spin, f = 5 slug ft^2/s): the rapid nutation riding on the slow
  % precession, as examples/report_figures.py draws them, here through the MEX gateway.
  %
  %   addpath <dir of gyro_mex.mex>; report_figures('figures')
  %
  % Writes figure_a1_pitch.png and figure_a2_yaw.png (GyroModel in double, the float model
  % overlaid). In Octave without a display: graphics_toolkit('gnuplot') first.
  [t, pitch, yaw] = run_sample('double');
  [~, pitch32, yaw32] = run_sample('single');
  n = min(numel(t), numel(pitch32));
  draw(t(1:n), pitch(1:n), pitch32(1:n), 'Figure A-1. Gyro pitch gimbal angle', 'pitch', ...
       fullfile(output_dir, 'figure_a1_pitch.png'));
  draw(t(1:n), yaw(1:n), yaw32(1:n), 'Figure A-2. Gyro yaw gimbal angle', 'yaw', ...
       fullfile(output_dir, 'figure_a2_yaw.png'));
end

% The sample's time and gimbal angles after each step, in a model of the given precision;
% stops on a flag as the report's driver does.
function [t, pitch, yaw] = run_sample(precision)
  s = gyro_mex('report_sample');
  model = gyro_mex('model_new', s.config, precision);
  dt = s.initg_step;
  turn = gyro_mex('frame_rotation', 'z', s.body_rate(2) * dt) * gyro_mex('frame_rotation', 'y', s.body_rate(1) * dt);
  body = eye(3);
  gyro_mex('model_uncage', model, body, s.body_rate);
  [t, pitch, yaw] = deal(zeros(s.steps, 1));
  for k = 1:s.steps
    body = turn * body;
    gyro_mex('model_step_slew', model, dt, s.slew, s.spin_hz, body);
    state = gyro_mex('model_state', model);
    t(k) = k * dt;
    pitch(k) = state.gimbal(1);
    yaw(k) = state.gimbal(2);
    if state.flags
      [t, pitch, yaw] = deal(t(1:k), pitch(1:k), yaw(1:k));
      break;
    end
  end
  gyro_mex('model_delete', model);
end

% One of the report's plots, written to a temporary file beside `path` and renamed over it
% once complete (a failed run leaves any older figure whole).
function draw(t, angle, angle32, title_text, label, path)
  f = figure('visible', 'off', 'paperunits', 'inches', 'paperposition', [0 0 8 5]);
  plot(t, angle * 180 / pi, '-', 'color', [0.12 0.31 0.61], 'linewidth', 1.0, ...
       t, angle32 * 180 / pi, '--', 'color', [0.84 0.15 0.16], 'linewidth', 0.8);
  xlabel('time (s)');
  ylabel(sprintf('%s gimbal angle (deg)', label));
  title(title_text);
  legend('GyroModel (double)', 'GyroModel (single)');
  grid on;
  [dir, name] = fileparts(path);
  if ~isempty(dir) && ~exist(dir, 'dir')
    mkdir(dir);
  end
  tmp = fullfile(dir, ['.' name '.png.tmp']);
  print(f, '-dpngcairo', '-r110', tmp);
  close(f);
  [ok, message] = movefile(tmp, path, 'f');
  if ~ok
    delete(tmp);
    error('report_figures:write', '%s: %s', path, message);
  end
  printf('%s\n', path);
end
