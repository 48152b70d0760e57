% The report's sample run (its driver GYMAIN, every error fixed) from MATLAB or Octave, through
% the MEX gateway gyro_mex. Prints the gimbal angles after the last step.
%   addpath <dir of gyro_mex.mex>; report_sample
sample = gyro_mex('report_sample');
model = gyro_mex('model_new', sample.config);  % a GyroModel kept until model_delete
dt = sample.initg_step;
% The body turns about its own pitch axis, then its yaw axis, every step.
turn = gyro_mex('frame_rotation', 'z', sample.body_rate(2) * dt) * ...
       gyro_mex('frame_rotation', 'y', sample.body_rate(1) * dt);
body = eye(3);
gyro_mex('model_uncage', model, body, sample.body_rate);
steps = 0;
state = gyro_mex('model_state', model);
while steps < sample.steps && state.flags == 0
  body = turn * body;  % the body's attitude at the step's end
  gyro_mex('model_step_slew', model, dt, sample.slew, sample.spin_hz, body);  % an error if refused
  steps = steps + 1;
  state = gyro_mex('model_state', model);
end
gyro_mex('model_delete', model);
printf('report sample: %d steps, gimbal pitch %.12e yaw %.12e rad\n', steps, state.gimbal(1), state.gimbal(2));
