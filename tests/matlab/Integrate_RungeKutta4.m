function [tout,yout] = Integrate_RungeKutta4(odefun,tspan,Ts,y0,par)
%The homework's 4th-order Runge-Kutta in the seed's convention (the classical
%tableau; Greenwood, "Advanced Dynamics"), the oracle of dynkit.integrate('rk4', ...).
tout=(tspan(1):Ts:tspan(end))';
numsteps=length(tout);
yout=zeros(numsteps,length(y0));
y_n=y0;
for n=1:numsteps
  t_n=tout(n);
  yout(n,:)=y_n;
  k1=feval(odefun,t_n,y_n',par)';
  k2=feval(odefun,t_n+Ts/2,(y_n+Ts/2*k1)',par)';
  k3=feval(odefun,t_n+Ts/2,(y_n+Ts/2*k2)',par)';
  k4=feval(odefun,t_n+Ts,(y_n+Ts*k3)',par)';
  y_n=y_n+Ts/6*(k1+2*k2+2*k3+k4);
end
